#include <lme_mpm/base/input.h>

#include <cctype>
#include <cmath>
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
  try
  {
    f.parse_parameters(prm);
    for (unsigned int c = 0; c < f.n_components; ++c)
      (void)f.value(dealii::Point<dim>(), c);
  }
  catch (...)
  {
    prm.leave_subsection();
    AssertThrow(false, ExcBadInput(entry + "/Function expression",
                                   "not a valid expression of the coordinates and t "
                                   "with " +
                                       std::to_string(f.n_components) +
                                       " components separated by ';'"));
  }
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
} // namespace input
} // namespace lme_mpm
