#ifndef LME_MPM_SHAPE_FUNCTIONS_LME_KERNELS_H
#define LME_MPM_SHAPE_FUNCTIONS_LME_KERNELS_H

// The arithmetic kernels of the local max-ent Newton solve (lme.cc): the exponential
// pass, the moments of the weights and the polynomial step. Kept apart from the
// shape function class so that the solve's numerics can be read (and benchmarked)
// on their own.

#include <deal.II/base/tensor.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

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

/**
 * Upper bound of the nodes within distance R of any point of a uniform product grid
 * of spacings @p h, close to the most a point has. The cell is cut into boxes, @p k
 * per direction (even); a box counts every node within R of some point of it (by the
 * node's distance to the box), which bounds the count of each of its points, and the
 * most over the boxes bounds every point. The grid is symmetric about the cell's
 * middle along each direction, so the boxes of one half suffice. With R = 2.77 h
 * (LME gamma 1.8) and k = 16: 27 nodes in 2D and 99 in 3D, where points reach 27 and
 * about 96 and nodes_in_ball_bound() gives 30 and 133.
 */
template <int dim>
unsigned int nodes_in_ball_on_lattice(const double R, const std::array<double, dim> &h,
                                      const unsigned int k = 16)
{
  const double R2 = R * R * (1 + 1e-12); // rounding must not drop a node
  // Per direction and box: the squared distances of the nodes along it that can lie
  // within R (node indices -m .. m + 1 around the cell [0, h]).
  std::array<std::vector<std::vector<double>>, dim> gap2;
  for (unsigned int d = 0; d < dim; ++d)
  {
    const int m = static_cast<int>(std::ceil(R / h[d])) + 1;
    gap2[d].resize(k / 2);
    for (unsigned int b = 0; b < k / 2; ++b)
    {
      const double lo = b * h[d] / k, hi = (b + 1) * h[d] / k;
      for (int i = -m; i <= m + 1; ++i)
      {
        const double gap = std::max({0.0, lo - i * h[d], i * h[d] - hi});
        if (gap * gap <= R2)
          gap2[d][b].push_back(gap * gap);
      }
    }
  }
  unsigned int most = 0;
  std::array<unsigned int, 3> box{};
  for (box[2] = 0; box[2] < (dim == 3 ? k / 2 : 1); ++box[2])
    for (box[1] = 0; box[1] < k / 2; ++box[1])
      for (box[0] = 0; box[0] < k / 2; ++box[0])
      {
        unsigned int count = 0;
        for (const double gy : gap2[1][box[1]])
          if constexpr (dim == 2)
          {
            for (const double gx : gap2[0][box[0]])
              count += gx + gy <= R2;
          }
          else
            for (const double gz : gap2[dim - 1][box[2]])
              for (const double gx : gap2[0][box[0]])
                count += gx + gy + gz <= R2;
        most = std::max(most, count);
      }
  return most;
}

/**
 * The most nodes whose supports can hold a point of one cell, over the cells of a
 * product grid with nodal coordinates @p coords, where node I reaches R_I =
 * radius_over_h h_I, h_I the smallest of its spacings @p node_h. On a graded grid
 * nodes_in_ball_bound() must take the widest support with the narrowest spacing, which
 * over-counts several times; the connectivity's rows are sized by this bound, and rows
 * mostly empty cost the transfers their memory traffic.
 */
template <int dim>
unsigned int nodes_within_reach_bound(const std::array<std::vector<double>, dim> &coords,
                                      const std::array<std::vector<double>, dim> &node_h,
                                      const double radius_over_h)
{
  struct Near
  {
    double gap2, h; ///< squared distance from the cell along one direction; spacing
  };
  double h_max = 0;
  for (unsigned int d = 0; d < dim; ++d)
    for (const double h : node_h[d])
      h_max = std::max(h_max, h);
  // Margins far above rounding: a node counted here that the set-up drops is harmless,
  // the reverse would stop a run.
  const double reach = radius_over_h * h_max * (1 + 1e-9);
  const double s2    = radius_over_h * radius_over_h * (1 + 1e-9);
  // Per direction and cell, the nodes within the widest reach of the cell along it; the
  // directions past dim hold one node at distance 0 that does not limit h_I.
  std::array<std::vector<std::vector<Near>>, 3> near;
  for (unsigned int d = 0; d < 3; ++d)
  {
    if (d >= dim)
    {
      near[d] = {{Near{0, std::numeric_limits<double>::infinity()}}};
      continue;
    }
    const auto &c = coords[d];
    near[d].resize(c.size() - 1);
    for (std::size_t cell = 0; cell + 1 < c.size(); ++cell)
      for (std::size_t i = 0; i < c.size(); ++i)
      {
        const double gap = std::max({0.0, c[cell] - c[i], c[i] - c[cell + 1]});
        if (gap <= reach)
          near[d][cell].push_back({gap * gap, node_h[d][i]});
      }
  }
  // Cells alike along a direction (a uniform stretch of a graded grid) have the same
  // list: only the distinct lists are combined, so the cost is that of the grid's
  // classes of cells, not of its cells. Gaps are rounded down and spacings up to 1e-12
  // (far inside the margins above) so that rounding does not split a class; the count
  // can only grow by it.
  for (unsigned int d = 0; d < dim; ++d)
  {
    const double gap_unit = 1e-12 * reach * reach, h_unit = 1e-12 * h_max;
    for (auto &list : near[d])
    {
      for (Near &n : list)
        n = {std::floor(n.gap2 / gap_unit) * gap_unit, std::ceil(n.h / h_unit) * h_unit};
      std::sort(list.begin(), list.end(),
                [](const Near &a, const Near &b)
                { return a.gap2 < b.gap2 || (a.gap2 == b.gap2 && a.h < b.h); });
    }
    const auto key = [](const std::vector<Near> &list)
    {
      std::vector<double> k;
      for (const Near &n : list)
        k.push_back(n.gap2), k.push_back(n.h);
      return k;
    };
    std::sort(near[d].begin(), near[d].end(),
              [&](const std::vector<Near> &a, const std::vector<Near> &b)
              { return key(a) < key(b); });
    near[d].erase(std::unique(near[d].begin(), near[d].end(),
                              [&](const std::vector<Near> &a, const std::vector<Near> &b)
                              { return key(a) == key(b); }),
                  near[d].end());
  }
  unsigned int most = 0;
  for (const auto &zs : near[2])
    for (const auto &ys : near[1])
      for (const auto &xs : near[0])
      {
        unsigned int n = 0;
        for (const Near &z : zs)
          for (const Near &y : ys)
          {
            const double gap2 = z.gap2 + y.gap2, h_yz = std::min(z.h, y.h);
            if (gap2 > s2 * h_yz * h_yz)
              continue;
            for (const Near &x : xs)
            {
              const double h = std::min(h_yz, x.h);
              n += (gap2 + x.gap2 <= s2 * h * h);
            }
          }
        most = std::max(most, n);
      }
  return most;
}
} // namespace lme_kernels
} // namespace shape_functions
} // namespace lme_mpm

#endif
