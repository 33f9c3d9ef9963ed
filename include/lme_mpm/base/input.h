#ifndef LME_MPM_BASE_INPUT_H
#define LME_MPM_BASE_INPUT_H

#include <deal.II/base/exceptions.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/parsed_function.h>
#include <deal.II/base/point.h>

#include <exception>
#include <map>
#include <string>
#include <vector>

namespace lme_mpm
{
/// An input value that is well formed but not allowed; the message names the entry.
DeclException2(ExcBadInput, std::string, std::string,
               << "Invalid input for '" << arg1 << "': " << arg2);

namespace input
{
/// "1, 2.5, 3" -> {1, 2.5, 3}; throws ExcBadInput naming @p entry on junk.
std::vector<double> parse_doubles(const std::string &text, const std::string &entry);

/// A point with exactly dim comma-separated coordinates.
template <int dim>
dealii::Point<dim> parse_point(const std::string &text, const std::string &entry);

/// Exactly @p n comma-separated names ("left, right"), trimmed; throws ExcBadInput
/// naming @p entry otherwise.
std::vector<std::string> parse_names(const std::string &text, unsigned int n,
                                     const std::string &entry);

/// "name(a, b, c)" -> name and arguments (a bare "name" gives no arguments).
struct Call
{
  std::string name;
  std::vector<double> args;
};
Call parse_call(const std::string &text, const std::string &entry);

/**
 * An entry's value with its unit and the range in which it is physical for the
 * materials this code is for (documented beside the entry). A message about a
 * quantity derived from several entries names them with their values, and an entry
 * outside its range first: that one is the likely typing error.
 */
struct EntryValue
{
  /// The entry's path, or a subsection whose entries stand together (value NaN).
  std::string entry;
  double value = 0;
  std::string unit;
  double low = 0, high = 0;

  bool physical() const { return value != value || (value >= low && value <= high); }
  /// "'E' = 1e+300 Pa (outside its physical range 1000 to 1e+13 Pa)", or "the
  /// entries of 'S'" for a value NaN.
  std::string describe() const;
};

/// @p values with the unphysical ones first (stable otherwise).
std::vector<EntryValue> unphysical_first(std::vector<EntryValue> values);

/// "'A' = 1 Pa, 'B' = 2 kg/m^3 and 'C' = 0.2", in the order given.
std::string describe_entries(const std::vector<EntryValue> &values);

/// Splits on a separator, trimming blanks and dropping empty pieces.
std::vector<std::string> split(const std::string &text, char separator);

std::string trim(const std::string &text);

/// The 'Additional information' of a deal.II exception (or what()), one paragraph.
std::string concise_message(const std::exception &e);

/// Throws ExcBadInput unless lo < value < hi (open) or lo <= value <= hi.
void require_range(double value, double lo, double hi, bool open,
                   const std::string &entry);
/// require_range(value, 0, 1e300, true, entry) for each (value, entry).
void require_positive(const std::vector<std::pair<double, std::string>> &values);

/**
 * Parses the ParsedFunction declared in subsection @p section of the current one.
 * muparser compiles on first use, so the function is evaluated once here: a syntax
 * error or a wrong number of components throws ExcBadInput naming @p entry.
 */
template <int dim>
void parse_function(dealii::ParameterHandler &prm, const std::string &section,
                    dealii::Functions::ParsedFunction<dim> &f, const std::string &entry);

/// True if a function expression uses x, y, z or t as a variable (a constant one can
/// be evaluated once).
bool depends_on_space_or_time(const std::string &expression);

/// "Kind N" with N counted from 1, the name of a repeated subsection.
std::string subsection_name(const std::string &kind, unsigned int i);

/**
 * Follows the subsections a parameter-file line opens or closes: pushes the name of a
 * "subsection NAME" line onto @p path, pops on "end". The path joined with '/', and a
 * trailing '/', is what path_prefix() gives.
 */
void follow_subsections(const std::string &line, std::vector<std::string> &path);

/// "A/B/" for the path {A, B}, "" for none.
std::string path_prefix(const std::vector<std::string> &path);

/// "Subsection/.../Entry" -> value of every 'set' line of a parameter-file text.
std::map<std::string, std::string> entry_values(const std::string &text);

/// Every entry @p prm declares, as "Subsection/.../Entry" paths.
std::vector<std::string> declared_entries(const dealii::ParameterHandler &prm);

/**
 * " (did you mean 'X'?)" for the candidate closest to @p wanted (edit distance,
 * ignoring case) when it is close enough to be a misspelling, "" otherwise. A path
 * is also compared by its last part alone, so an entry given in the wrong subsection
 * finds its right one.
 */
std::string did_you_mean(const std::string &wanted,
                         const std::vector<std::string> &candidates);

/**
 * What to add to a deal.II "does not match the pattern" message about @p value: for a
 * selection, the closest of its names and where plug-in names come from.
 */
std::string selection_hint(const std::string &value, const std::string &message);
} // namespace input
} // namespace lme_mpm

#endif
