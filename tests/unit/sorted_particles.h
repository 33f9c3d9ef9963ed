// Particles placed in a store sorted by the cells of a grid, as the solver keeps them
// (what Neighbourhood::build() reads).
#ifndef LME_MPM_TESTS_SORTED_PARTICLES_H
#define LME_MPM_TESTS_SORTED_PARTICLES_H

#include <lme_mpm/grid/background_grid.h>
#include <lme_mpm/particles/particle_store.h>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace lme_mpm_test
{
using namespace lme_mpm;

/// Locates the particles of @p store in @p grid and sorts the store by cell.
template <int dim>
void sort_by_grid_cells(ParticleStore<dim> &store, const BackgroundGrid<dim> &grid)
{
  for (std::size_t p = 0; p < store.size(); ++p)
  {
    std::array<unsigned int, dim> ijk;
    ASSERT_TRUE(grid.locate(store.position[p], ijk)) << "particle " << p;
    store.cell[p] = grid.cell_index(ijk);
  }
  store.sort_by_cell(grid.n_cells());
}

/**
 * A store of the points @p x (body ids @p body, or 0), on a grid of cells of @p h from
 * a cell below the points' lowest coordinate to beyond their highest, sorted by cell.
 */
template <int dim>
ParticleStore<dim> sorted_store(const std::vector<Point<dim>> &x,
                                const std::vector<std::uint16_t> &body, const double h,
                                BackgroundGrid<dim> &grid)
{
  Point<dim> lo = x[0], hi = x[0];
  for (const Point<dim> &p : x)
    for (unsigned int d = 0; d < dim; ++d)
      lo[d] = std::min(lo[d], p[d]), hi[d] = std::max(hi[d], p[d]);
  std::array<std::vector<double>, dim> steps;
  for (unsigned int d = 0; d < dim; ++d)
  {
    lo[d] -= h;
    steps[d].assign(static_cast<std::size_t>(std::ceil((hi[d] - lo[d]) / h)) + 1, h);
  }
  grid.reinit(lo, steps);
  ParticleStore<dim> store;
  for (std::size_t p = 0; p < x.size(); ++p)
    store.add(x[p], 1.0, 1.0, 0, body.empty() ? 0 : body[p]);
  sort_by_grid_cells(store, grid);
  return store;
}
} // namespace lme_mpm_test

#endif
