#ifndef LME_MPM_BASE_PARAMETERS_H
#define LME_MPM_BASE_PARAMETERS_H

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <type_traits>

namespace lme_mpm
{
/**
 * One list of parameter entries that serves both to declare them and to read them
 * into the members they set. A part writes `void entries(EntryList &list)` with one
 * `list.add(name, member, default, pattern, documentation)` per entry; declaring
 * and parsing both call it, so an entry's name, default and pattern are written
 * once, next to the member.
 *
 * Declaring needs no object with state: a part's static declare_parameters() runs
 * the list on a default-constructed instance whose members only receive nothing.
 */
class EntryList
{
public:
  enum class Mode
  {
    declare,
    parse
  };

  EntryList(dealii::ParameterHandler &prm, const Mode mode) : prm(prm), mode(mode) {}

  bool parsing() const { return mode == Mode::parse; }

  /// Declares the entries of @p Entries (a struct with entries(EntryList &)) in the
  /// current subsection of @p prm.
  template <class Entries>
  static void declare(dealii::ParameterHandler &prm)
  {
    EntryList list(prm, Mode::declare);
    Entries().entries(list);
  }
  /// Reads them from the current subsection of @p prm.
  template <class Entries>
  static Entries parse(dealii::ParameterHandler &prm)
  {
    Entries values;
    EntryList list(prm, Mode::parse);
    values.entries(list);
    return values;
  }

  void enter(const std::string &section) { prm.enter_subsection(section); }
  void leave() { prm.leave_subsection(); }

  /// Declares the entry (declare mode) or reads it into @p value (parse mode).
  template <class T>
  void add(const std::string &name, T &value, const std::string &default_value,
           const dealii::Patterns::PatternBase &pattern, const std::string &documentation)
  {
    if (mode == Mode::declare)
    {
      prm.declare_entry(name, default_value, pattern, documentation);
      return;
    }
    if constexpr (std::is_same_v<T, bool>)
      value = prm.get_bool(name);
    else if constexpr (std::is_integral_v<T>)
      value = static_cast<T>(prm.get_integer(name));
    else if constexpr (std::is_floating_point_v<T>)
      value = prm.get_double(name);
    else
      value = trim(prm.get(name));
  }

private:
  /// Text entries without surrounding blanks (names are compared as written).
  static std::string trim(const std::string &text)
  {
    const auto b = text.find_first_not_of(" \t\n\r");
    return b == std::string::npos
               ? ""
               : text.substr(b, text.find_last_not_of(" \t\n\r") + 1 - b);
  }

  dealii::ParameterHandler &prm;
  const Mode mode;
};
} // namespace lme_mpm

#endif
