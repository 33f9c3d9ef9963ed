#ifndef LME_MPM_SHAPE_FUNCTIONS_TENSOR_PRODUCT_H
#define LME_MPM_SHAPE_FUNCTIONS_TENSOR_PRODUCT_H

#include <lme_mpm/shape_functions/shape_function.h>

#include <array>

namespace lme_mpm
{
/**
 * Builds a particle's row of the connectivity from 1D weights per direction: node
 * index i0[d] + k along d carries value w[d][k] and derivative dw[d][k], k < n[d].
 * Shared by the separable families (linear, uGIMP, B-spline). Nodes come out in
 * increasing index order (the fastest direction first).
 */
template <int dim, int max_1d>
inline unsigned int
tensor_product_row(const BackgroundGrid<dim> &grid,
                   const std::array<unsigned int, dim> &i0,
                   const std::array<unsigned int, dim> &n,
                   const std::array<std::array<double, max_1d>, dim> &w,
                   const std::array<std::array<double, max_1d>, dim> &dw,
                   unsigned int *nodes, double *N, Tensor<1, dim> *grad_N)
{
  unsigned int count = 0;
  if constexpr (dim == 2)
  {
    for (unsigned int b = 0; b < n[1]; ++b)
      for (unsigned int a = 0; a < n[0]; ++a)
      {
        nodes[count]     = grid.node_index({{i0[0] + a, i0[1] + b}});
        N[count]         = w[0][a] * w[1][b];
        grad_N[count][0] = dw[0][a] * w[1][b];
        grad_N[count][1] = w[0][a] * dw[1][b];
        ++count;
      }
  }
  else
  {
    for (unsigned int c = 0; c < n[2]; ++c)
      for (unsigned int b = 0; b < n[1]; ++b)
        for (unsigned int a = 0; a < n[0]; ++a)
        {
          nodes[count]     = grid.node_index({{i0[0] + a, i0[1] + b, i0[2] + c}});
          N[count]         = w[0][a] * w[1][b] * w[2][c];
          grad_N[count][0] = dw[0][a] * w[1][b] * w[2][c];
          grad_N[count][1] = w[0][a] * dw[1][b] * w[2][c];
          grad_N[count][2] = w[0][a] * w[1][b] * dw[2][c];
          ++count;
        }
  }
  return count;
}
} // namespace lme_mpm

#endif
