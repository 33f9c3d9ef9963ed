#ifndef LME_MPM_BASE_DEALII_H
#define LME_MPM_BASE_DEALII_H

// The one place that lets the project's namespace see deal.II's names (Tensor, Point,
// ParameterHandler, ...) unqualified; every header that uses them includes this one
// instead of repeating the directive.
namespace dealii
{
}

namespace lme_mpm
{
using namespace dealii;
} // namespace lme_mpm

#endif
