#ifndef LME_MPM_BASE_FORMAT_H
#define LME_MPM_BASE_FORMAT_H

#include <deal.II/base/point.h>

#include <string>

namespace lme_mpm
{
/// Formats a point for error messages: "(x, y)" with 10 significant digits.
template <int dim>
std::string point_to_string(const dealii::Point<dim> &p);
/// A number for error messages, 6 significant digits ("inf", "nan" as such).
std::string format_double(double value);
} // namespace lme_mpm

#endif
