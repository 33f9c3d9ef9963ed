#ifndef LME_MPM_DISTRIBUTED_CELL_BOXES_H
#define LME_MPM_DISTRIBUTED_CELL_BOXES_H

// Private to the library (not installed): box queries on the cells of a grid, for the
// halo of a distributed run.

#include <lme_mpm/distributed/halo.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

namespace lme_mpm
{
/**
 * Boxes of cells on a grid of n[d] cells per direction: tells whether a box holds a
 * flagged cell (summed-area table) and flags the union of many boxes (a difference
 * array), each in O(1) per box, so halos of any width cost O(cells) per pass.
 */
template <int dim>
class CellBoxes
{
public:
  using Box = CellBox<dim>;

  explicit CellBoxes(const std::array<unsigned int, dim> &n) : n(n)
  {
    std::size_t s = 1;
    for (unsigned int d = 0; d < dim; ++d)
      stride[d] = s, s *= n[d] + 1;
    values.resize(s);
  }

  /// Makes any() answer for the cells flagged in @p mask (lexicographic order).
  void tabulate(const std::vector<std::uint8_t> &mask)
  {
    std::fill(values.begin(), values.end(), 0);
    for_cells([&](const std::size_t c, const std::array<unsigned int, dim> &ijk)
              { values[corner(ijk, 1)] = mask[c]; });
    prefix_sums();
  }
  bool any(const Box &b) const
  {
    std::int64_t count = 0;
    for (unsigned int k = 0; k < (1u << dim); ++k)
    {
      std::size_t at = 0;
      int sign       = 1;
      for (unsigned int d = 0; d < dim; ++d)
        if (k & (1u << d))
          at += stride[d] * b.hi[d];
        else
          at += stride[d] * b.lo[d], sign = -sign;
      count += sign * values[at];
    }
    return count != 0;
  }

  /// Starts flagging boxes.
  void clear() { std::fill(values.begin(), values.end(), 0); }
  void paint(const Box &b)
  {
    for (unsigned int k = 0; k < (1u << dim); ++k)
    {
      std::size_t at = 0;
      int sign       = 1;
      for (unsigned int d = 0; d < dim; ++d)
        if (k & (1u << d))
          at += stride[d] * b.hi[d], sign = -sign;
        else
          at += stride[d] * b.lo[d];
      values[at] += sign;
    }
  }
  /// Flags in @p mask (ORed) every cell inside a painted box.
  void painted(std::vector<std::uint8_t> &mask)
  {
    prefix_sums();
    for_cells([&](const std::size_t c, const std::array<unsigned int, dim> &ijk)
              { mask[c] |= values[corner(ijk, 0)] > 0; });
  }

  template <class F>
  void for_cells(F &&f) const
  {
    std::array<unsigned int, dim> ijk{};
    std::size_t n_cells = 1;
    for (unsigned int d = 0; d < dim; ++d)
      n_cells *= n[d];
    for (std::size_t c = 0; c < n_cells; ++c)
    {
      f(c, ijk);
      for (unsigned int d = 0; d < dim && ++ijk[d] == n[d]; ++d)
        ijk[d] = 0;
    }
  }

private:
  std::size_t corner(const std::array<unsigned int, dim> &ijk,
                     const unsigned int shift) const
  {
    std::size_t at = 0;
    for (unsigned int d = 0; d < dim; ++d)
      at += stride[d] * (ijk[d] + shift);
    return at;
  }
  void prefix_sums()
  {
    for (unsigned int d = 0; d < dim; ++d)
      for (std::size_t f = 0; f < values.size(); ++f)
        if ((f / stride[d]) % (n[d] + 1) != 0)
          values[f] += values[f - stride[d]];
  }

  std::array<unsigned int, dim> n;
  std::array<std::size_t, dim> stride;
  std::vector<std::int64_t> values;
};

/// Cells of @p c (node coordinates) within @p r of [a, b], as [lo, hi).
inline void cells_near(const std::vector<double> &c, const double a, const double b,
                       const double r, unsigned int &lo, unsigned int &hi)
{
  // A cell [c[m], c[m+1]] is near if c[m+1] >= a - r and c[m] <= b + r; a hair of
  // slack keeps a boundary case in.
  const double slack = 1e-12 * (c.back() - c.front());
  const auto first   = std::lower_bound(c.begin(), c.end(), a - r - slack);
  const auto last    = std::upper_bound(c.begin(), c.end(), b + r + slack);
  const long n_cells = static_cast<long>(c.size()) - 1;
  lo = static_cast<unsigned int>(std::max<long>(0, (first - c.begin()) - 1));
  hi = static_cast<unsigned int>(std::min<long>(n_cells, last - c.begin()));
  lo = std::min(lo, hi);
}
} // namespace lme_mpm

#endif
