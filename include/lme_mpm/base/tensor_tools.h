#ifndef LME_MPM_BASE_TENSOR_TOOLS_H
#define LME_MPM_BASE_TENSOR_TOOLS_H

#include <deal.II/base/symmetric_tensor.h>

namespace lme_mpm
{
/// Largest eigenvalue of a symmetric tensor (the max principal stress or strain).
template <int dim>
inline double max_principal(const dealii::SymmetricTensor<2, dim> &t)
{
  return dealii::eigenvalues(t)[0];
}
} // namespace lme_mpm

#endif
