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
 */
template <int dim>
inline double max_principal(const dealii::SymmetricTensor<2, dim> &t)
{
  if constexpr (dim == 2)
    return 0.5 * (t[0][0] + t[1][1]) + std::hypot(0.5 * (t[0][0] - t[1][1]), t[0][1]);
  else
    return dealii::eigenvalues(t)[0];
}
} // namespace lme_mpm

#endif
