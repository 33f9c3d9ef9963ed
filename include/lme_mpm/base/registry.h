#ifndef LME_MPM_BASE_REGISTRY_H
#define LME_MPM_BASE_REGISTRY_H

#include <deal.II/base/exceptions.h>
#include <deal.II/base/parameter_handler.h>

#include <lme_mpm/base/parameters.h>

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

namespace lme_mpm
{
/**
 * Who is registering plug-ins now (the lme-mpm library itself, or the plug-in library
 * PluginLibraries is loading) and the registrations refused so far because their
 * name was taken: a plug-in cannot replace a built-in or another library's plug-in
 * behind the user's back. One object for the whole process (defined in the library).
 */
struct RegistrationLog
{
  std::string current = "the lme-mpm library";
  std::vector<std::string> refused;
};
RegistrationLog &registration_log();

/**
 * Name-indexed entries, the storage and look-up every registry shares (the plug-in
 * registries below and the shapes of geometry.h). Names are kept sorted, so listings
 * do not depend on the order in which plug-ins registered themselves.
 */
template <class Entry>
class NamedEntries
{
public:
  /**
   * Adds @p name unless it is taken, in which case the first registration stays and
   * the refusal is logged (registration_log()). Returns true so that it can
   * initialise a static variable.
   */
  bool add(const std::string &name, Entry entry)
  {
    RegistrationLog &log = registration_log();
    const auto taken     = owners.find(name);
    if (taken != owners.end())
    {
      log.refused.push_back("'" + name + "' is registered by " + taken->second +
                            " and again by " + log.current +
                            " (the first registration is kept; rename the plug-in)");
      return true;
    }
    owners[name]  = log.current;
    entries[name] = std::move(entry);
    return true;
  }

  bool contains(const std::string &name) const { return entries.count(name) > 0; }

  /// The entry registered as @p name, or nullptr.
  const Entry *find(const std::string &name) const
  {
    const auto it = entries.find(name);
    return it == entries.end() ? nullptr : &it->second;
  }

  /// Names joined by '|', the form Patterns::Selection takes.
  std::string pattern() const
  {
    std::string s;
    for (const auto &e : entries)
      s += (s.empty() ? "" : "|") + e.first;
    return s;
  }

  const std::map<std::string, Entry> &all() const { return entries; }

private:
  std::map<std::string, Entry> entries;
  /// Who registered each name.
  std::map<std::string, std::string> owners;
};

/// What a plug-in registry keeps of one plug-in (see Registry).
template <class Base, class Context>
struct PluginEntry
{
  /// Declares the plug-in's entries in the current subsection.
  using Declare = std::function<void(dealii::ParameterHandler &)>;
  /// Builds the plug-in from the parsed entries in the current subsection.
  using Create =
      std::function<std::unique_ptr<Base>(dealii::ParameterHandler &, const Context &)>;

  std::string description;
  Declare declare;
  Create create;
  /// False: the entries go straight into the caller's subsection.
  bool own_subsection = true;
};

/**
 * A name-indexed registry of plug-ins (materials, shape functions, softening laws,
 * fracture models). Each plug-in registers itself from a static object in its own
 * translation unit, so a user adds one by linking a source file: the core never
 * lists the implementations. The library is shared, so registrations are never
 * dropped by the linker. Plug-ins register through register_plugin() or
 * register_plugin_for_dims(), which the LME_MPM_REGISTER_* macros call.
 *
 * @tparam Base the interface; @tparam Context what a constructor needs besides the
 * parsed parameters (for example the problem setup).
 */
template <class Base, class Context>
class Registry : public NamedEntries<PluginEntry<Base, Context>>
{
public:
  using base_type    = Base;
  using context_type = Context;
  using Entry        = PluginEntry<Base, Context>;
  using Declare      = typename Entry::Declare;
  using Create       = typename Entry::Create;

  static Registry &instance()
  {
    static Registry registry;
    return registry;
  }

  /// Documentation of all plug-ins, for the selection entry.
  std::string documentation() const
  {
    std::string s;
    for (const auto &e : this->all())
      s += "'" + e.first + "': " + e.second.description + " ";
    return s;
  }

  /// Declares every plug-in's entries, each in a subsection named after it unless
  /// the plug-in declares into the caller's subsection.
  void declare_all(dealii::ParameterHandler &prm) const
  {
    for (const auto &e : this->all())
      if (e.second.declare)
      {
        if (e.second.own_subsection)
          prm.enter_subsection(e.first);
        e.second.declare(prm);
        if (e.second.own_subsection)
          prm.leave_subsection();
      }
  }

  std::unique_ptr<Base> create(const std::string &name, dealii::ParameterHandler &prm,
                               const Context &context) const
  {
    const Entry *entry = this->find(name);
    AssertThrow(entry != nullptr,
                dealii::ExcMessage("Unknown plug-in '" + name +
                                   "'; registered: " + this->pattern()));
    const bool enter = entry->declare && entry->own_subsection;
    if (enter)
      prm.enter_subsection(name);
    auto object = entry->create(prm, context);
    if (enter)
      prm.leave_subsection();
    return object;
  }
};

/// Where a plug-in's parameter entries go (see register_plugin()).
enum class PluginEntries
{
  none,             ///< the plug-in declares no entries
  own_subsection,   ///< a subsection named after the plug-in (materials)
  caller_subsection ///< straight into the caller's subsection (shape functions)
};

namespace internal
{
/// True if Plugin has a static declare_parameters(ParameterHandler &).
template <class Plugin, class = void>
struct HasDeclareParameters : std::false_type
{
};
template <class Plugin>
struct HasDeclareParameters<Plugin, std::void_t<decltype(Plugin::declare_parameters(
                                        std::declval<dealii::ParameterHandler &>()))>>
    : std::true_type
{
};
/// True if Plugin names the struct of its entries (Plugin::Entries, with
/// entries(EntryList &)).
template <class Plugin, class = void>
struct HasEntries : std::false_type
{
};
template <class Plugin>
struct HasEntries<Plugin, std::void_t<typename Plugin::Entries>> : std::true_type
{
};
} // namespace internal

/**
 * Registers class @p Plugin (derived from RegistryType::base_type) as @p name in
 * RegistryType::instance(). The plug-in is built from (ParameterHandler &, const
 * Context &) if it has such a constructor, else from (const Context &); its static
 * declare_parameters(ParameterHandler &), if any, or else the struct Plugin::Entries
 * it names (entries(EntryList &), the one list it also reads), declares its entries
 * unless @p where is PluginEntries::none. Returns true so that it can initialise a
 * static variable.
 */
template <class RegistryType, class Plugin>
bool register_plugin(const std::string &name, const std::string &description,
                     const PluginEntries where)
{
  using Base    = typename RegistryType::base_type;
  using Context = typename RegistryType::context_type;
  static_assert(std::is_base_of_v<Base, Plugin>, "a plug-in derives from its interface");
  typename RegistryType::Entry entry;
  entry.description = description;
  if constexpr (internal::HasDeclareParameters<Plugin>::value)
  {
    if (where != PluginEntries::none)
      entry.declare = [](dealii::ParameterHandler &prm)
      { Plugin::declare_parameters(prm); };
  }
  else if constexpr (internal::HasEntries<Plugin>::value)
  {
    if (where != PluginEntries::none)
      entry.declare = [](dealii::ParameterHandler &prm)
      { EntryList::declare<typename Plugin::Entries>(prm); };
  }
  entry.own_subsection = where == PluginEntries::own_subsection;
  entry.create         = [](dealii::ParameterHandler &prm, const Context &context)
  {
    if constexpr (std::is_constructible_v<Plugin, dealii::ParameterHandler &,
                                          const Context &>)
      return std::unique_ptr<Base>(new Plugin(prm, context));
    else
    {
      (void)prm;
      return std::unique_ptr<Base>(new Plugin(context));
    }
  };
  return RegistryType::instance().add(name, std::move(entry));
}

/// register_plugin() of Plugin<dim> in RegistryOf<dim> for dim = 2 and 3.
template <template <int> class RegistryOf, template <int> class Plugin>
bool register_plugin_for_dims(const std::string &name, const std::string &description,
                              const PluginEntries where)
{
  const bool in_2d = register_plugin<RegistryOf<2>, Plugin<2>>(name, description, where);
  const bool in_3d = register_plugin<RegistryOf<3>, Plugin<3>>(name, description, where);
  return in_2d && in_3d;
}
} // namespace lme_mpm

/// A name of its own for each registration: the class may be given with its namespace
/// (my_plugins::PowerLaw), which cannot be part of a variable's name.
#define LME_MPM_CONCATENATE_(A, B) A##B
#define LME_MPM_CONCATENATE(A, B) LME_MPM_CONCATENATE_(A, B)
#define LME_MPM_UNIQUE_NAME(PREFIX) LME_MPM_CONCATENATE(PREFIX, __COUNTER__)

/**
 * The core of the LME_MPM_REGISTER_* macros of a registry that is not templated on
 * dim: registers class CLASS in REGISTRY from a static initialiser. KIND keeps the
 * variable apart from other registrations of CLASS in the same file.
 */
#define LME_MPM_REGISTER_PLUGIN(REGISTRY, KIND, CLASS, NAME, DESCRIPTION, WHERE)         \
  namespace                                                                              \
  {                                                                                      \
  const bool LME_MPM_UNIQUE_NAME(lme_mpm_registered_##KIND##_) =                         \
      ::lme_mpm::register_plugin<REGISTRY, CLASS>(NAME, DESCRIPTION, WHERE);             \
  }

/**
 * The core of the LME_MPM_REGISTER_* macros of a registry templated on dim
 * (REGISTRY<dim>): registers the class template CLASS
 * (templated on dim) in REGISTRY<2> and REGISTRY<3> from a static initialiser.
 */
#define LME_MPM_REGISTER_PLUGIN_FOR_DIMS(REGISTRY, KIND, CLASS, NAME, DESCRIPTION,       \
                                         WHERE)                                          \
  namespace                                                                              \
  {                                                                                      \
  const bool LME_MPM_UNIQUE_NAME(lme_mpm_registered_##KIND##_) =                         \
      ::lme_mpm::register_plugin_for_dims<REGISTRY, CLASS>(NAME, DESCRIPTION, WHERE);    \
  }

#endif
