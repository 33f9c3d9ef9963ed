#ifndef LME_MPM_FRACTURE_CELL_SEARCH_H
#define LME_MPM_FRACTURE_CELL_SEARCH_H

#include <deal.II/base/bounding_box.h>

#include <lme_mpm/grid/background_grid.h>

#include <algorithm>
#include <array>
#include <type_traits>
#include <vector>

namespace lme_mpm
{
/**
 * The cells of a background grid that come within a radius of a point, in increasing
 * cell index. The particle store is sorted by cell (ParticleStore::sort_by_cell), so
 * visiting these cells' particles in this order visits them in increasing particle
 * index: a neighbour list built this way is sorted without sorting it, and no binning
 * of its own is needed. Works on graded grids (each direction's own coordinates).
 */
template <int dim>
class CellSearch
{
  static_assert(dim == 2 || dim == 3, "a search over 2D or 3D grids");

public:
  /// Per-thread room for the per-direction gaps (kept between calls).
  using Scratch = std::array<std::vector<double>, dim>;

  explicit CellSearch(const BackgroundGrid<dim> &grid) : grid(grid) {}

  /**
   * Calls f(c) for every cell c whose closed box lies within @p radius of @p x, in
   * increasing c. A cell is skipped only if its box is farther than the radius (with a
   * relative slack of 1e-12 on the squared radius against round-off), so every point
   * of the grid within the radius lies in a visited cell. An f that returns bool
   * stops the walk by returning true, and for_cells_near() then returns true (a
   * question answered by the first cell that has the answer).
   */
  template <class F>
  bool for_cells_near(const Point<dim> &x, const double radius, Scratch &gaps,
                      F &&f) const
  {
    const auto visit = [&](const std::size_t c)
    {
      if constexpr (std::is_same_v<std::invoke_result_t<F &, std::size_t>, bool>)
        return f(c);
      else
      {
        f(c);
        return false;
      }
    };
    std::array<unsigned int, dim> lo, hi;
    for (unsigned int d = 0; d < dim; ++d)
    {
      const std::vector<double> &c = grid.coordinates(d);
      const double a               = std::clamp(x[d] - radius, c.front(), c.back()),
                   b               = std::clamp(x[d] + radius, c.front(), c.back());
      grid.locate(a, d, lo[d]);
      grid.locate(b, d, hi[d]);
      // One cell more on each side: a point on a face is located in the upper cell,
      // and the gap test below settles which cells count.
      lo[d] -= lo[d] > 0 ? 1 : 0;
      hi[d] += hi[d] + 1 < grid.n_cells_in(d) ? 1 : 0;
      gaps[d].resize(hi[d] - lo[d] + 1);
      for (unsigned int i = lo[d]; i <= hi[d]; ++i)
      {
        const double g     = std::max({0.0, c[i] - x[d], x[d] - c[i + 1]});
        gaps[d][i - lo[d]] = g * g;
      }
    }
    const double limit    = radius * radius * (1 + 1e-12);
    const unsigned int nx = grid.n_cells_in(0);
    if constexpr (dim == 2)
    {
      for (unsigned int j = lo[1]; j <= hi[1]; ++j)
      {
        const double gy = gaps[1][j - lo[1]];
        if (gy > limit)
          continue;
        for (unsigned int i = lo[0]; i <= hi[0]; ++i)
          if (gy + gaps[0][i - lo[0]] <= limit && visit(i + nx * j))
            return true;
      }
    }
    else
    {
      const unsigned int nxy = nx * grid.n_cells_in(1);
      for (unsigned int k = lo[2]; k <= hi[2]; ++k)
      {
        const double gz = gaps[2][k - lo[2]];
        if (gz > limit)
          continue;
        for (unsigned int j = lo[1]; j <= hi[1]; ++j)
        {
          const double gyz = gz + gaps[1][j - lo[1]];
          if (gyz > limit)
            continue;
          for (unsigned int i = lo[0]; i <= hi[0]; ++i)
            if (gyz + gaps[0][i - lo[0]] <= limit && visit(i + nx * j + nxy * k))
              return true;
        }
      }
    }
    return false;
  }

  /// The closed box of cell @p c.
  BoundingBox<dim> box(const std::size_t c) const
  {
    Point<dim> lo, hi;
    std::size_t rest = c;
    for (unsigned int d = 0; d < dim; ++d)
    {
      const unsigned int i = rest % grid.n_cells_in(d);
      rest /= grid.n_cells_in(d);
      lo[d] = grid.coordinates(d)[i], hi[d] = grid.coordinates(d)[i + 1];
    }
    return BoundingBox<dim>({lo, hi});
  }

private:
  const BackgroundGrid<dim> &grid;
};
} // namespace lme_mpm

#endif
