#include <lme_mpm/base/input.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <iostream>
#include <sstream>

namespace lme_mpm
{
namespace input
{
std::string trim(const std::string &text)
{
  const auto b = text.find_first_not_of(" \t\n\r");
  if (b == std::string::npos)
    return "";
  const auto e = text.find_last_not_of(" \t\n\r");
  return text.substr(b, e - b + 1);
}

std::string concise_message(const std::exception &e)
{
  std::string text      = e.what();
  const std::string key = "Additional information:";
  const auto pos        = text.find(key);
  if (pos != std::string::npos)
    text = text.substr(pos + key.size());
  const auto dashes = text.find("\n----");
  if (dashes != std::string::npos)
    text = text.substr(0, dashes);
  const auto stack = text.find("Stacktrace:");
  if (stack != std::string::npos)
    text = text.substr(0, stack);
  // Fold the indented lines into one paragraph.
  std::string out;
  bool space = false;
  for (const char c : text)
    if (c == '\n' || c == ' ' || c == '\t')
      space = !out.empty();
    else
    {
      if (space)
        out += ' ';
      out += c;
      space = false;
    }
  return out;
}

std::vector<std::string> split(const std::string &text, const char separator)
{
  std::vector<std::string> out;
  std::stringstream ss(text);
  std::string piece;
  while (std::getline(ss, piece, separator))
  {
    piece = trim(piece);
    if (!piece.empty())
      out.push_back(piece);
  }
  return out;
}

std::vector<double> parse_doubles(const std::string &text, const std::string &entry)
{
  std::vector<double> values;
  for (const auto &piece : split(text, ','))
  {
    std::size_t used = 0;
    double v         = 0;
    try
    {
      v = std::stod(piece, &used);
    }
    catch (...)
    {
      used = 0;
    }
    AssertThrow(used == piece.size() && std::isfinite(v),
                ExcBadInput(entry, "'" + piece + "' is not a finite number"));
    values.push_back(v);
  }
  return values;
}

std::vector<std::string> parse_names(const std::string &text, const unsigned int n,
                                     const std::string &entry)
{
  const auto names = split(text, ',');
  AssertThrow(names.size() == n,
              ExcBadInput(entry, "needs " + std::to_string(n) +
                                     " comma-separated names, got '" + text + "'"));
  return names;
}

template <int dim>
dealii::Point<dim> parse_point(const std::string &text, const std::string &entry)
{
  const auto v = parse_doubles(text, entry);
  AssertThrow(v.size() == dim,
              ExcBadInput(entry, "expected " + std::to_string(dim) +
                                     " comma-separated coordinates, got '" + text + "'"));
  dealii::Point<dim> p;
  for (unsigned int d = 0; d < dim; ++d)
    p[d] = v[d];
  return p;
}

Call parse_call(const std::string &text, const std::string &entry)
{
  const std::string t = trim(text);
  const auto open     = t.find('(');
  Call call;
  if (open == std::string::npos)
  {
    call.name = t;
    return call;
  }
  AssertThrow(t.back() == ')',
              ExcBadInput(entry, "expected name(arguments), got '" + text + "'"));
  call.name = trim(t.substr(0, open));
  call.args = parse_doubles(t.substr(open + 1, t.size() - open - 2), entry);
  return call;
}

bool depends_on_space_or_time(const std::string &expr)
{
  for (const char *v : {"x", "y", "z", "t"})
    for (std::size_t pos = expr.find(v); pos != std::string::npos;
         pos             = expr.find(v, pos + 1))
    {
      const bool left_ok =
          pos == 0 || !(std::isalnum(expr[pos - 1]) || expr[pos - 1] == '_');
      const bool right_ok = pos + 1 >= expr.size() ||
                            !(std::isalnum(expr[pos + 1]) || expr[pos + 1] == '_');
      if (left_ok && right_ok)
        return true;
    }
  return false;
}

std::string EntryValue::describe() const
{
  if (std::isnan(value))
    return "the entries of '" + entry + "'";
  std::ostringstream s;
  const std::string space = unit.empty() ? "" : " " + unit;
  s << "'" << entry << "' = " << value << space;
  if (!physical())
    s << " (outside its physical range " << low << " to " << high << space << ")";
  return s.str();
}

std::vector<EntryValue> unphysical_first(std::vector<EntryValue> values)
{
  std::stable_partition(values.begin(), values.end(),
                        [](const EntryValue &v) { return !v.physical(); });
  return values;
}

std::string describe_entries(const std::vector<EntryValue> &values)
{
  std::string s;
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    if (i > 0)
      s += i + 1 == values.size() ? " and " : ", ";
    s += values[i].describe();
  }
  return s;
}

void require_range(const double value, const double lo, const double hi, const bool open,
                   const std::string &entry)
{
  const bool ok = open ? (value > lo && value < hi) : (value >= lo && value <= hi);
  std::ostringstream msg;
  msg << "value " << value << " is outside the allowed range " << (open ? "(" : "[") << lo
      << ", " << hi << (open ? ")" : "]");
  AssertThrow(ok, ExcBadInput(entry, msg.str()));
}

void require_positive(const std::vector<std::pair<double, std::string>> &values)
{
  for (const auto &[value, entry] : values)
    require_range(value, 0, 1e300, true, entry);
}

template dealii::Point<2> parse_point<2>(const std::string &, const std::string &);
template dealii::Point<3> parse_point<3>(const std::string &, const std::string &);
template <int dim>
void parse_function(dealii::ParameterHandler &prm, const std::string &section,
                    dealii::Functions::ParsedFunction<dim> &f, const std::string &entry)
{
  prm.enter_subsection(section);
  const std::string expression = prm.get("Function expression"),
                    variables  = prm.get("Variable names");
  // deal.II prints muParser's own report to std::cerr before it throws: keep it
  // for the one-line message instead.
  std::ostringstream parser_report;
  std::streambuf *const console = std::cerr.rdbuf(parser_report.rdbuf());
  try
  {
    f.parse_parameters(prm);
    for (unsigned int c = 0; c < f.n_components; ++c)
      (void)f.value(dealii::Point<dim>(), c);
  }
  catch (...)
  {
    std::cerr.rdbuf(console);
    prm.leave_subsection();
    const std::string report = parser_report.str(), tag = "Token:";
    std::string token;
    if (const auto at = report.find(tag); at != std::string::npos)
    {
      const auto open = report.find('<', at), close = report.find('>', open);
      if (open != std::string::npos && close != std::string::npos)
        token = report.substr(open + 1, close - open - 1);
    }
    std::string message = "'" + expression + "' is not an expression of " + variables +
                          " with " + std::to_string(f.n_components) +
                          " component(s) separated by ';'";
    if (!token.empty())
      message += ": '" + token + "' is not a known function, variable or constant " +
                 "(constants are defined in '" + entry + "/Function constants')";
    AssertThrow(false, ExcBadInput(entry + "/Function expression", message));
  }
  std::cerr.rdbuf(console);
  prm.leave_subsection();
}

template void parse_function<2>(dealii::ParameterHandler &, const std::string &,
                                dealii::Functions::ParsedFunction<2> &,
                                const std::string &);
template void parse_function<3>(dealii::ParameterHandler &, const std::string &,
                                dealii::Functions::ParsedFunction<3> &,
                                const std::string &);

std::string subsection_name(const std::string &kind, const unsigned int i)
{
  return kind + " " + std::to_string(i + 1);
}

void follow_subsections(const std::string &line, std::vector<std::string> &path)
{
  const std::string text = trim(line.substr(0, line.find('#')));
  if (text.rfind("subsection ", 0) == 0)
    path.push_back(trim(text.substr(11)));
  else if (text == "end" && !path.empty())
    path.pop_back();
}

std::string path_prefix(const std::vector<std::string> &path)
{
  std::string prefix;
  for (const auto &p : path)
    prefix += p + "/";
  return prefix;
}

std::map<std::string, std::string> entry_values(const std::string &text)
{
  std::map<std::string, std::string> values;
  std::vector<std::string> path;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line))
  {
    line = trim(line);
    if (line.rfind("set ", 0) != 0)
    {
      follow_subsections(line, path);
      continue;
    }
    const auto eq = line.find('=');
    if (eq != std::string::npos)
      values[path_prefix(path) + trim(line.substr(4, eq - 4))] =
          trim(line.substr(eq + 1));
  }
  return values;
}

std::vector<std::string> declared_entries(const dealii::ParameterHandler &prm)
{
  // The short PRM form lists the tree as "subsection", "set" and "end" lines.
  std::ostringstream text;
  prm.print_parameters(text, dealii::ParameterHandler::ShortPRM);
  std::vector<std::string> entries;
  for (const auto &[path, value] : entry_values(text.str()))
    entries.push_back(path);
  return entries;
}

namespace
{
std::size_t edit_distance(const std::string &a, const std::string &b)
{
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
    row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
  {
    std::size_t diagonal = row[0];
    row[0]               = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
    {
      const std::size_t above = row[j];
      const bool same         = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                        std::tolower(static_cast<unsigned char>(b[j - 1]));
      row[j]   = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string last_part(const std::string &path)
{
  const auto slash = path.rfind('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}
} // namespace

std::string did_you_mean(const std::string &wanted,
                         const std::vector<std::string> &candidates)
{
  std::string best;
  double best_score = 1e9;
  for (const auto &c : candidates)
  {
    // Relative to the longer string's length, so that short names need a closer
    // match; the last parts alone score a little worse than a match of the paths.
    const double whole =
        double(edit_distance(wanted, c)) /
        double(std::max<std::size_t>(std::max(wanted.size(), c.size()), 1));
    const std::string a = last_part(wanted), b = last_part(c);
    const double last =
        0.05 + double(edit_distance(a, b)) /
                   double(std::max<std::size_t>(std::max(a.size(), b.size()), 1));
    const double score = std::min(whole, last);
    if (score < best_score && c != wanted)
    {
      best_score = score;
      best       = c;
    }
  }
  return best_score <= 0.34 ? " (did you mean '" + best + "'?)" : "";
}

std::string selection_hint(const std::string &value, const std::string &message)
{
  const std::string tag = "[Selection ";
  const auto at         = message.find(tag);
  if (at == std::string::npos)
    return "";
  const auto end   = message.find(']', at);
  const auto names = split(message.substr(at + tag.size(), end == std::string::npos
                                                               ? std::string::npos
                                                               : end - at - tag.size()),
                           '|');
  return did_you_mean(trim(value), names) +
         "; a name that a plug-in registers is known once its library is loaded with "
         "'Additional shared libraries'";
}
} // namespace input
} // namespace lme_mpm
