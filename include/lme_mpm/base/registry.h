#ifndef LME_MPM_BASE_REGISTRY_H
#define LME_MPM_BASE_REGISTRY_H

#include <deal.II/base/exceptions.h>
#include <deal.II/base/parameter_handler.h>

#include <functional>
#include <map>
#include <memory>
#include <string>

namespace lme_mpm
{
/**
 * A name-indexed registry of plug-ins (materials, shape functions, softening laws,
 * geometries). Each plug-in registers itself from a static object in its own
 * translation unit, so a user adds one by linking a source file: the core never
 * lists the implementations. The library is shared, so registrations are never
 * dropped by the linker.
 *
 * @tparam Base the interface; @tparam Context what a constructor needs besides the
 * parsed parameters (for example the problem setup).
 */
template <class Base, class Context>
class Registry
{
public:
  /// Declares the plug-in's entries in the current subsection.
  using Declare = std::function<void(dealii::ParameterHandler &)>;
  /// Builds the plug-in from the parsed entries in the current subsection.
  using Create =
      std::function<std::unique_ptr<Base>(dealii::ParameterHandler &, const Context &)>;

  struct Entry
  {
    std::string description;
    Declare declare;
    Create create;
    /// False: the entries go straight into the caller's subsection.
    bool own_subsection = true;
  };

  static Registry &instance()
  {
    static Registry registry;
    return registry;
  }

  /// Returns true so that it can initialise a static variable.
  bool add(const std::string &name, Entry entry)
  {
    entries[name] = std::move(entry);
    return true;
  }

  bool contains(const std::string &name) const { return entries.count(name) > 0; }

  /// Names joined by '|', the form Patterns::Selection takes.
  std::string pattern() const
  {
    std::string s;
    for (const auto &e : entries)
      s += (s.empty() ? "" : "|") + e.first;
    return s;
  }

  /// Documentation of all plug-ins, for the selection entry.
  std::string documentation() const
  {
    std::string s;
    for (const auto &e : entries)
      s += "'" + e.first + "': " + e.second.description + " ";
    return s;
  }

  /// Declares every plug-in's entries, each in a subsection named after it.
  void declare_all(dealii::ParameterHandler &prm) const
  {
    for (const auto &e : entries)
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
    const auto it = entries.find(name);
    AssertThrow(it != entries.end(), dealii::ExcMessage("Unknown plug-in '" + name +
                                                        "'; registered: " + pattern()));
    const bool enter = it->second.declare && it->second.own_subsection;
    if (enter)
      prm.enter_subsection(name);
    auto object = it->second.create(prm, context);
    if (enter)
      prm.leave_subsection();
    return object;
  }

  const std::map<std::string, Entry> &all() const { return entries; }

private:
  std::map<std::string, Entry> entries;
};
} // namespace lme_mpm

#endif
