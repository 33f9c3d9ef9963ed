// Neighbourhood rows limited to the particles near a seed are the full rows there (on
// a graded grid).
#include <deal.II/base/parameter_handler.h>

#include <gtest/gtest.h>

#include <lme_mpm/base/stage_timer.h>
#include <lme_mpm/fracture/fracture_model.h>
#include <lme_mpm/fracture/neighbourhood.h>

#include "sorted_particles.h"
#include "test_helpers.h"

#include <cmath>
#include <random>
#include <thread>

using namespace lme_mpm;

namespace
{
template <int dim>
void check_seeded_rows(const unsigned int n, const double radius, const double share)
{
  std::mt19937 rng(5 + dim);
  std::uniform_real_distribution<double> u(0, 1);
  // Random points in the unit square or cube on a graded grid (cells from 0.02 to
  // 0.06 wide, some narrower and some wider than the radius), sorted by its cells as
  // the solver's store is.
  std::array<std::vector<double>, dim> steps;
  for (unsigned int d = 0; d < dim; ++d)
    for (double x = 0; x < 1 - 1e-12;)
    {
      const double s = std::min(1 - x, 0.02 + 0.04 * u(rng));
      steps[d].push_back(s), x += s;
    }
  BackgroundGrid<dim> grid;
  grid.reinit(Point<dim>(), steps);
  ParticleStore<dim> store;
  for (unsigned int p = 0; p < n; ++p)
  {
    Point<dim> x;
    for (unsigned int d = 0; d < dim; ++d)
      x[d] = u(rng);
    store.add(x, 1.0, 1.0, 0, x[0] < 0.5 ? 0 : 1);
  }
  lme_mpm_test::sort_by_grid_cells(store, grid);
  const std::vector<Point<dim>> &x = store.position;
  std::vector<std::uint8_t> seeds(n);
  for (unsigned int p = 0; p < n; ++p)
    // Seeds at random; seven particles in ten take a row.
    seeds[p] = (u(rng) < share ? Neighbourhood<dim>::seed : 0) |
               (u(rng) < 0.7 ? Neighbourhood<dim>::takes_row : 0);
  Neighbourhood<dim> full, seeded;
  full.build(store, grid, radius);
  seeded.build(store, grid, radius, {}, &seeds);
  std::size_t rows = 0;
  for (unsigned int p = 0; p < n; ++p)
  {
    bool near = false;
    for (unsigned int q = 0; q < n && !near && (seeds[p] & Neighbourhood<dim>::takes_row);
         ++q)
      near = (seeds[q] & Neighbourhood<dim>::seed) && x[p].distance(x[q]) <= radius;
    ASSERT_EQ(seeded.has_row(p), near) << "particle " << p;
    rows += near;
    if (near)
      ASSERT_EQ(std::vector<std::uint32_t>(seeded.begin(p), seeded.end(p)),
                std::vector<std::uint32_t>(full.begin(p), full.end(p)))
          << "particle " << p;
    else
      ASSERT_EQ(seeded.begin(p), seeded.end(p));
  }
  EXPECT_EQ(seeded.n_rows(), rows);
  EXPECT_GT(rows, 0u);
  EXPECT_LT(rows, n); // some particles were skipped, so the check means something
  EXPECT_EQ(full.n_rows(), n);

  // No seed, or no particle that takes a row: no row at all.
  for (const std::uint8_t keep :
       {Neighbourhood<dim>::takes_row, Neighbourhood<dim>::seed})
  {
    for (auto &f : seeds)
      f &= keep;
    seeded.build(store, grid, radius, {}, &seeds);
    EXPECT_EQ(seeded.n_rows(), 0u);
    for (unsigned int p = 0; p < n; ++p)
      ASSERT_FALSE(seeded.has_row(p));
  }
}

} // namespace

TEST(Neighbourhood, SeededRowsAreTheFullRowsNearASeed2D)
{
  check_seeded_rows<2>(3000, 0.03, 0.002);
}

TEST(Neighbourhood, SeededRowsAreTheFullRowsNearASeed3D)
{
  check_seeded_rows<3>(3000, 0.08, 0.002);
}
