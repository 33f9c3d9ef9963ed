#ifndef LME_MPM_FRACTURE_CUBE_BINS_H
#define LME_MPM_FRACTURE_CUBE_BINS_H

#include <deal.II/base/point.h>

#include <lme_mpm/base/dealii.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace lme_mpm
{
/**
 * A cell-linked list: points binned into cubes of a given side over their bounding
 * box by a stable counting sort, so that the points within that distance of any
 * point lie in the 3^dim cubes around it, and each cube lists its points in
 * ascending index order. Building costs two passes over the points.
 */
template <int dim>
class CubeBins
{
public:
  /// Bins @p x (at least one point) into cubes of side @p side.
  void build(const std::vector<Point<dim>> &x, double side);

  std::size_t n_bins() const { return bin_start.size() - 1; }
  /// The cube of point @p p.
  std::uint32_t bin_of(const std::size_t p) const { return bins[p]; }
  /// The points of cube @p b, ascending: [begin(b), end(b)).
  const std::uint32_t *begin(const std::size_t b) const
  {
    return sorted.data() + bin_start[b];
  }
  const std::uint32_t *end(const std::size_t b) const
  {
    return sorted.data() + bin_start[b + 1];
  }

  /// Calls g(b) for the (up to 3^dim) cubes around point @p x, in increasing order.
  template <class G>
  void for_cubes(const Point<dim> &x, G &&g) const
  {
    std::array<std::uint32_t, dim> c;
    index(x, c);
    std::array<int, dim> k;
    k.fill(-1);
    while (true)
    {
      bool inside   = true;
      std::size_t b = 0, stride = 1;
      for (unsigned int d = 0; d < dim; ++d)
      {
        const long j = long(c[d]) + k[d];
        inside       = inside && j >= 0 && j < long(n[d]);
        b += std::size_t(std::max(0L, j)) * stride;
        stride *= n[d];
      }
      if (inside)
        g(b);
      unsigned int d = 0;
      while (d < dim && ++k[d] > 1)
        k[d++] = -1;
      if (d == dim)
        break;
    }
  }

private:
  /// The cube of @p x (and its index along each direction).
  std::size_t index(const Point<dim> &x, std::array<std::uint32_t, dim> &ijk) const
  {
    std::size_t b = 0, stride = 1;
    for (unsigned int d = 0; d < dim; ++d)
    {
      ijk[d] = std::min<std::uint32_t>(n[d] - 1, (x[d] - lo[d]) / side);
      b += ijk[d] * stride;
      stride *= n[d];
    }
    return b;
  }

  Point<dim> lo;
  double side = 1;
  std::array<std::uint32_t, dim> n{};
  // Kept between builds.
  std::vector<std::uint32_t> bins, bin_start, sorted;
};

template <int dim>
void CubeBins<dim>::build(const std::vector<Point<dim>> &x, const double side_)
{
  const std::size_t count = x.size();
  side                    = side_;
  lo                      = x[0];
  Point<dim> hi           = x[0];
  for (std::size_t p = 0; p < count; ++p)
    for (unsigned int d = 0; d < dim; ++d)
      lo[d] = std::min(lo[d], x[p][d]), hi[d] = std::max(hi[d], x[p][d]);
  std::size_t total = 1;
  for (unsigned int d = 0; d < dim; ++d)
  {
    n[d] =
        static_cast<std::uint32_t>(std::min(1e6, std::floor((hi[d] - lo[d]) / side)) + 1);
    total *= n[d];
  }
  // Counting sort of the indices by cube (stable: each cube's list ascends).
  bins.resize(count);
  bin_start.assign(total + 1, 0);
  for (std::size_t p = 0; p < count; ++p)
  {
    std::array<std::uint32_t, dim> ijk;
    bins[p] = index(x[p], ijk);
    ++bin_start[bins[p] + 1];
  }
  for (std::size_t b = 0; b < total; ++b)
    bin_start[b + 1] += bin_start[b];
  sorted.resize(count);
  std::vector<std::uint32_t> next(bin_start.begin(), bin_start.end() - 1);
  for (std::size_t p = 0; p < count; ++p)
    sorted[next[bins[p]]++] = static_cast<std::uint32_t>(p);
}
} // namespace lme_mpm

#endif
