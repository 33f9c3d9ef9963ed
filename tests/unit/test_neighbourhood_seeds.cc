// Neighbourhood rows limited to the particles near a seed are the full rows there.
#include <deal.II/base/parameter_handler.h>

#include <gtest/gtest.h>

#include <lme_mpm/base/stage_timer.h>
#include <lme_mpm/fracture/fracture_model.h>
#include <lme_mpm/fracture/neighbourhood.h>

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
  std::vector<Point<dim>> x(n);
  for (auto &p : x)
    for (unsigned int d = 0; d < dim; ++d)
      p[d] = u(rng);
  std::vector<std::uint16_t> body(n);
  std::vector<std::uint8_t> seeds(n);
  for (unsigned int p = 0; p < n; ++p)
  {
    body[p] = x[p][0] < 0.5 ? 0 : 1;
    // Seeds at random; seven particles in ten take a row.
    seeds[p] = (u(rng) < share ? Neighbourhood<dim>::seed : 0) |
               (u(rng) < 0.7 ? Neighbourhood<dim>::takes_row : 0);
  }
  Neighbourhood<dim> full, seeded;
  full.build(x, radius, &body);
  seeded.build(x, radius, &body, {}, &seeds);
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
    seeded.build(x, radius, &body, {}, &seeds);
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
