#ifndef LME_MPM_SHAPE_FUNCTIONS_LME_KERNELS_H
#define LME_MPM_SHAPE_FUNCTIONS_LME_KERNELS_H

// The arithmetic kernels of the local max-ent Newton solve (lme.cc): the exponential
// pass, the moments of the weights and the polynomial step. Kept apart from the
// shape function class so that the solve's numerics can be read (and benchmarked)
// on their own.

#include <deal.II/base/tensor.h>

#include <array>
#include <cmath>
#include <limits>

#ifdef LME_MPM_EIGEN_EXP
#include <Eigen/Core>
#endif

namespace lme_mpm
{
namespace shape_functions
{
namespace lme_kernels
{
using namespace dealii;

/// v[i] = exp(v[i] - shift) for i < n: the single largest cost of an LME evaluation.
inline void exponentiate(double *v, const unsigned int n, const double shift)
{
#ifdef LME_MPM_EIGEN_EXP
  // Eigen's packet exp: two (SSE2) or four (AVX) exponentials per instruction.
  Eigen::Map<Eigen::ArrayXd> a(v, n);
  a = (a - shift).exp();
#else
  for (unsigned int i = 0; i < n; ++i)
    v[i] = std::exp(v[i] - shift);
#endif
}

/// Raw moments sum w_I, sum w_I y_I and the upper triangle of sum w_I y_I y_I^T (3D;
/// 2D goes through the passes of lme_simd.h).
template <int dim>
inline void raw_moments(const double *w, const Tensor<1, dim> *y, const unsigned int n,
                        double &Z, Tensor<1, dim> &r, Tensor<2, dim> &J)
{
  Z = 0, r = 0, J = 0;
  for (unsigned int I = 0; I < n; ++I)
  {
    const double e = w[I];
    Z += e;
    for (unsigned int i = 0; i < dim; ++i)
    {
      r[i] += e * y[I][i];
      for (unsigned int j = i; j < dim; ++j)
        J[i][j] += e * y[I][i] * y[I][j];
    }
  }
}

/// N_I = w_I / Z, r and J the mean and covariance of the y_I under them; returns log Z.
template <int dim>
inline double normalise(double *N, const Tensor<1, dim> *y, const unsigned int n,
                        Tensor<1, dim> &r, Tensor<2, dim> &J)
{
  double Z;
  raw_moments(N, y, n, Z, r, J);
  const double inv_Z = 1 / Z;
  for (unsigned int I = 0; I < n; ++I)
    N[I] *= inv_Z;
  r *= inv_Z;
  for (unsigned int i = 0; i < dim; ++i)
    for (unsigned int j = i; j < dim; ++j)
      J[j][i] = J[i][j] = J[i][j] * inv_Z - r[i] * r[j];
  return std::log(Z);
}

/// F = log Z, N, r = d log Z / d mu and J = d r / d mu at mu (scaled lambda).
template <int dim>
inline void evaluate(const double *a, const Tensor<1, dim> *y, const unsigned int n,
                     const Tensor<1, dim> &mu, double *N, double &F, Tensor<1, dim> &r,
                     Tensor<2, dim> &J)
{
  double f_max = -std::numeric_limits<double>::infinity();
  for (unsigned int I = 0; I < n; ++I)
  {
    N[I]  = a[I] + mu * y[I];
    f_max = std::max(f_max, N[I]);
  }
  exponentiate(N, n, f_max);
  F = f_max + normalise(N, y, n, r, J);
}

/// evaluate() at mu + step from its results at mu, without exponentials: N_I(mu + step)
/// is proportional to N_I(mu) exp(t), t = step . (y_I - r), here the cubic Taylor
/// polynomial of exp(t); the normalisation absorbs the common factor exactly.
template <int dim>
inline void polynomial_step(const Tensor<1, dim> *y, const unsigned int n,
                            const Tensor<1, dim> &step, double *N, double &F,
                            Tensor<1, dim> &r, Tensor<2, dim> &J)
{
  for (unsigned int I = 0; I < n; ++I)
  {
    const double t = step * (y[I] - r);
    N[I] *= 1 + t * (1 + t * (0.5 + t * (1. / 6)));
  }
  const double step_r = step * r; // log Z(mu + step) - log Z(mu) = step . r + log S
  F += step_r + normalise(N, y, n, r, J);
}
/**
 * Upper bound of the nodes within distance R of any point, on a product grid whose
 * spacing along d is at least h[d]. The planes (rows) of nodes sorted by distance
 * from the point: the i-th is at least i h / 2 away (i + 1 of them span i h), and
 * a row holds at most floor(2 rho / h_x) + 1 nodes within rho of it.
 */
template <int dim>
unsigned int nodes_in_ball_bound(const double R, const std::array<double, dim> &h)
{
  const double R2   = R * R * (1 + 1e-12); // rounding must not drop a node
  const auto in_row = [&](const double rho2)
  { return static_cast<unsigned int>(std::floor(2 * std::sqrt(rho2) / h[0])) + 1; };
  unsigned int count = 0;
  for (unsigned int i = 0; i * h[dim - 1] / 2 <= std::sqrt(R2); ++i)
  {
    const double dz2 = std::pow(i * h[dim - 1] / 2, 2);
    if constexpr (dim == 2)
      count += in_row(R2 - dz2);
    else
      for (unsigned int j = 0; j * h[1] / 2 <= std::sqrt(R2 - dz2); ++j)
        count += in_row(R2 - dz2 - std::pow(j * h[1] / 2, 2));
  }
  return count;
}
} // namespace lme_kernels
} // namespace shape_functions
} // namespace lme_mpm

#endif
