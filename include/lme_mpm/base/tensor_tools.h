#ifndef LME_MPM_BASE_TENSOR_TOOLS_H
#define LME_MPM_BASE_TENSOR_TOOLS_H

#include <deal.II/base/symmetric_tensor.h>

#include <cmath>

namespace lme_mpm
{
/**
 * Largest eigenvalue of a symmetric tensor (the max principal stress or strain). In 2D
 * a closed form without cancellation: deal.II's tr^2 - 4 det can round below zero for
 * a nearly isotropic tensor with a tiny shear (an assertion in its debug library).
 * Non-finite entries give a non-finite result, which the callers test for.
 */
template <int dim>
inline double max_principal(const dealii::SymmetricTensor<2, dim> &t)
{
  if constexpr (dim == 2)
  {
    // sqrt of the sum of squares, not std::hypot: the same radius without hypot's
    // guard against overflow (squares overflow only above 1e154), at a fraction of
    // its cost in the per-particle stress snapshot.
    const double a = 0.5 * (t[0][0] - t[1][1]), b = t[0][1];
    return 0.5 * (t[0][0] + t[1][1]) + std::sqrt(a * a + b * b);
  }
  else
    return dealii::eigenvalues(t)[0];
}
} // namespace lme_mpm

#endif
