#include <lme_mpm/base/format.h>

#include <sstream>

namespace lme_mpm
{
template <int dim>
std::string point_to_string(const dealii::Point<dim> &p)
{
  std::ostringstream s;
  s.precision(10);
  s << "(";
  for (unsigned int d = 0; d < dim; ++d)
    s << (d ? ", " : "") << p[d];
  s << ")";
  return s.str();
}

std::string format_double(const double value)
{
  std::ostringstream s;
  s << value;
  return s.str();
}

template std::string point_to_string<2>(const dealii::Point<2> &);
template std::string point_to_string<3>(const dealii::Point<3> &);
} // namespace lme_mpm
