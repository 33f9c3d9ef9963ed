// Neighbourhood: the epsilon-neighbourhood against brute force, within a body and on
// one side of a crack.
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/parameter_handler.h>

#include <gtest/gtest.h>

#include <lme_mpm/fracture/crack_set.h>
#include <lme_mpm/fracture/fracture_coupling.h>
#include <lme_mpm/fracture/fracture_model.h>
#include <lme_mpm/fracture/neighbourhood.h>
#include <lme_mpm/fracture/softening_law.h>

#include "sorted_particles.h"
#include "test_helpers.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <iostream>
#include <random>

using namespace lme_mpm;
using lme_mpm_test::sorted_store;

namespace
{
/// Random particles in the unit cube; with @p body, body(x) gives each one's body.
template <int dim>
void check_neighbourhood_against_brute_force(
    const unsigned int n, const double radius,
    const std::function<std::uint16_t(const Point<dim> &)> &body = {})
{
  std::mt19937 rng(11 + dim);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Point<dim>> x(n);
  for (auto &p : x)
    for (unsigned int d = 0; d < dim; ++d)
      p[d] = u(rng);
  std::vector<std::uint16_t> ids(n, 0);
  if (body)
    std::transform(x.begin(), x.end(), ids.begin(), body);
  // Cells smaller than the radius, so that rows span several cells.
  BackgroundGrid<dim> grid;
  const ParticleStore<dim> store = sorted_store(x, ids, 0.6 * radius, grid);
  Neighbourhood<dim> nb;
  nb.build(store, grid, radius);
  ASSERT_EQ(nb.size(), n);
  const std::vector<Point<dim>> &y = store.position;
  for (unsigned int p = 0; p < n; ++p)
  {
    std::vector<std::uint32_t> brute;
    for (unsigned int q = 0; q < n; ++q)
      if (y[p].distance(y[q]) <= radius && store.body_id[p] == store.body_id[q])
        brute.push_back(q);
    ASSERT_EQ(std::vector<std::uint32_t>(nb.begin(p), nb.end(p)), brute)
        << "particle " << p;
  }
}

} // namespace

TEST(Neighbourhood, AgreesWithBruteForce2D)
{
  check_neighbourhood_against_brute_force<2>(3000, 0.04);
}

TEST(Neighbourhood, AgreesWithBruteForce3D)
{
  check_neighbourhood_against_brute_force<3>(2000, 0.12);
}

TEST(Neighbourhood, StaysWithinTheParticlesOwnBody)
{
  // Two rectangles touching along x = 0.5, and a third body of scattered particles
  // inside the second: no row holds a particle of another body.
  check_neighbourhood_against_brute_force<2>(
      3000, 0.04,
      [](const Point<2> &p) {
        return std::uint16_t(p[0] < 0.5 ? 0 : (std::fmod(p[1] * 100, 1) < 0.1 ? 7 : 1));
      });
  check_neighbourhood_against_brute_force<3>(
      2000, 0.12, [](const Point<3> &p) { return std::uint16_t(p[2] < 0.5 ? 3 : 2); });
  // One body throughout: every particle within the radius, as without body ids.
  check_neighbourhood_against_brute_force<2>(3000, 0.04,
                                             [](const Point<2> &) { return 5; });
  // Thread-count independent.
  std::vector<Point<2>> x;
  std::vector<std::uint16_t> body;
  for (unsigned int i = 0; i < 60; ++i)
    for (unsigned int j = 0; j < 40; ++j)
      x.emplace_back(0.01 * i, 0.01 * j), body.push_back(i < 30 ? 0 : 1);
  BackgroundGrid<2> grid;
  const ParticleStore<2> store = sorted_store(x, body, 0.02, grid);
  Neighbourhood<2> one, two;
  MultithreadInfo::set_thread_limit(1);
  one.build(store, grid, 0.025);
  MultithreadInfo::set_thread_limit(2);
  two.build(store, grid, 0.025);
  MultithreadInfo::set_thread_limit();
  ASSERT_EQ(one.n_pairs(), two.n_pairs());
  for (std::size_t p = 0; p < x.size(); ++p)
    ASSERT_TRUE(std::equal(one.begin(p), one.end(p), two.begin(p), two.end(p))) << p;
}

TEST(Neighbourhood, StaysOnItsSideOfAnExplicitCrack)
{
  // A crack with a kink across part of the unit square: no row holds a particle whose
  // straight line to the particle crosses it, unless the path round an end of the
  // crack is within the radius (near a tip); every other pair within the radius is
  // kept (checked against a brute-force segment intersection).
  const std::vector<std::vector<Point<2>>> lines = {
      {Point<2>(-0.1, 0.5), Point<2>(0.4, 0.5), Point<2>(0.7, 0.62)},
      {Point<2>(0.2, 0.1), Point<2>(0.2, 0.3)}};
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Point<2>> points(3000);
  for (auto &p : points)
    p = Point<2>(u(rng), u(rng));
  const double radius = 0.05;
  BackgroundGrid<2> grid;
  const ParticleStore<2> store   = sorted_store(points, {}, 0.03, grid);
  const std::vector<Point<2>> &x = store.position;
  CrackSegmentBins<2> bins;
  bins.build(lines, radius);
  Neighbourhood<2> nb, asked;
  const auto separated = [&](const std::size_t p, const std::size_t q)
  { return bins.separates(x[p], x[q]); };
  nb.build(store, grid, radius, separated);
  // Asking only the rows that may be cut (those near a segment) gives the same rows,
  // and most rows of this square never ask.
  asked.build(store, grid, radius, separated, nullptr,
              [&](const std::size_t p) { return bins.may_separate(x[p]); });
  std::size_t far = 0;
  for (std::size_t p = 0; p < x.size(); ++p)
  {
    far += !bins.may_separate(x[p]);
    ASSERT_EQ(std::vector<std::uint32_t>(nb.begin(p), nb.end(p)),
              std::vector<std::uint32_t>(asked.begin(p), asked.end(p)))
        << "particle " << p;
  }
  EXPECT_GT(far, x.size() / 4);
  EXPECT_LT(far, x.size());
  const auto cross =
      [](const Point<2> &a, const Point<2> &b, const Point<2> &c, const Point<2> &d)
  {
    const auto side = [](const Point<2> &o, const Point<2> &e, const Point<2> &f)
    { return (e[0] - o[0]) * (f[1] - o[1]) - (e[1] - o[1]) * (f[0] - o[0]); };
    return side(a, b, c) * side(a, b, d) < 0 && side(c, d, a) * side(c, d, b) < 0;
  };
  std::size_t cut = 0, round_tip = 0;
  for (std::size_t p = 0; p < x.size(); ++p)
  {
    std::vector<std::uint32_t> brute;
    for (std::size_t q = 0; q < x.size(); ++q)
    {
      if (x[p].distance(x[q]) > radius)
        continue;
      bool cut_off = false, near_tip = false;
      for (const auto &line : lines)
        for (std::size_t k = 0; k + 1 < line.size(); ++k)
          if (cross(x[p], x[q], line[k], line[k + 1]))
          {
            const double detour =
                std::min(x[p].distance(line.front()) + line.front().distance(x[q]),
                         x[p].distance(line.back()) + line.back().distance(x[q]));
            cut_off  = cut_off || detour > radius;
            near_tip = near_tip || detour <= radius;
          }
      if (cut_off)
        ++cut;
      else
        brute.push_back(q);
      round_tip += near_tip && !cut_off;
    }
    ASSERT_EQ(std::vector<std::uint32_t>(nb.begin(p), nb.end(p)), brute)
        << "particle " << p;
  }
  EXPECT_GT(cut, 1000u);     // the crack does cut pairs
  EXPECT_GT(round_tip, 20u); // and keeps some round its tips
}

TEST(Neighbourhood, BuildTimePerParticle)
{
  // 2D, 4 particles per cell of 1 mm, eps = 2 mm (C_eps = 2): about 50 neighbours each.
  std::vector<Point<2>> x;
  for (unsigned int i = 0; i < 400; ++i)
    for (unsigned int j = 0; j < 250; ++j)
      x.emplace_back(0.5e-3 * i + 0.25e-3, 0.5e-3 * j + 0.25e-3);
  BackgroundGrid<2> grid;
  const ParticleStore<2> store = sorted_store(x, {}, 1e-3, grid);
  Neighbourhood<2> nb;
  nb.build(store, grid, 2e-3);
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < 5; ++k)
    nb.build(store, grid, 2e-3);
  const double ns =
      std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start)
          .count() /
      (5.0 * x.size());
  std::cout << "neighbourhood build: " << ns << " ns per particle, "
            << double(nb.n_pairs()) / x.size() << " neighbours per particle" << std::endl;
  EXPECT_GT(nb.n_pairs(), 40 * x.size());
}

namespace
{
/**
 * Particles that drift a little each step and are sorted by cell again, as in a run:
 * rows kept with a skin, once cut to the radius, equal those of a fresh build, on
 * either side of a crack, with seeds that come and go; and the lists are made anew
 * only now and then. @p with_reaches: the kept rows are cut to each particle's own
 * reach (Neighbourhood::cut_rows_to(), some beyond the radius), and equal the fresh
 * rows cut to it.
 */
template <int dim>
void check_kept_lists_against_fresh_builds(const bool with_crack,
                                           const bool with_reaches = false)
{
  std::mt19937 rng(5 + dim + 10 * with_crack + 100 * with_reaches);
  std::uniform_real_distribution<double> u(0, 1);
  const unsigned int n = dim == 2 ? 3000 : 2500;
  const double radius  = dim == 2 ? 0.04 : 0.12;
  std::vector<Point<dim>> x(n);
  std::vector<std::uint16_t> body(n);
  for (unsigned int p = 0; p < n; ++p)
  {
    for (unsigned int d = 0; d < dim; ++d)
      x[p][d] = 0.1 + 0.8 * u(rng);
    body[p] = x[p][0] < 0.3 ? 1 : 0;
  }
  BackgroundGrid<dim> grid;
  // Room for the drift: two particles of a body without rows at corners of the unit
  // cube stretch the grid over it.
  x.push_back(Point<dim>());
  x.push_back(Point<dim>());
  for (unsigned int d = 0; d < dim; ++d)
    x.back()[d] = 1;
  body.resize(x.size(), 2);
  ParticleStore<dim> store = sorted_store(x, body, 0.6 * radius, grid);
  const std::size_t m      = store.size();
  // In 2D a straight crack through the middle.
  const std::vector<std::vector<Point<2>>> crack = {
      {Point<2>(0.2, 0.5), Point<2>(0.6, 0.5)}};
  CrackSegmentBins<2> bins;
  if constexpr (dim == 2)
    bins.build(crack, radius);
  const auto separated = [&](const std::size_t p, const std::size_t q)
  {
    if constexpr (dim == 2)
      return bins.separates(store.position[p], store.position[q]);
    else
      return false;
  };
  const auto may_be_separated = [&](const std::size_t p)
  {
    if constexpr (dim == 2)
      return bins.may_separate(store.position[p]);
    else
      return true;
  };
  const double skin = 0.1 * radius;
  Neighbourhood<dim> kept, fresh;
  kept.keep_lists(skin);
  std::vector<std::uint8_t> seeds(m);
  // Reaches that belong to the particles (by id): a half, four fifths and 1.3 times
  // the radius.
  std::vector<double> reach(m);
  if (with_reaches)
    kept.cut_rows_to(&reach);
  const unsigned int steps = 40;
  std::size_t compared = 0, cut_rows = 0, reorders = 0, kept_pairs = 0, fresh_pairs = 0;
  for (unsigned int step = 0; step < steps; ++step)
  {
    for (std::size_t p = 0; p < m; ++p)
      reach[p] = radius * std::array<double, 3>{{0.5, 0.8, 1.3}}[store.id[p] % 3];
    // Seeds in a patch that widens; rows taken by most particles.
    for (std::size_t p = 0; p < m; ++p)
    {
      double r = 0;
      for (unsigned int d = 0; d < dim; ++d)
        r += std::pow(store.position[p][d] - 0.45, 2);
      const bool seed_here = std::sqrt(r) < 0.1 + 0.002 * step;
      seeds[p] =
          (seed_here ? Neighbourhood<dim>::seed : 0) |
          (store.body_id[p] != 2 && store.id[p] % 20 != 0 ? Neighbourhood<dim>::takes_row
                                                          : 0);
    }
    // A change of order other than a sort (as an exchange between ranks makes): that
    // build's rows hold the particles within the radius only.
    const bool exchanged = step == 20;
    if (exchanged)
      store.mark_reordered();
    const std::size_t searches = kept.n_list_builds();
    if (with_crack)
    {
      kept.build(store, grid, radius, separated, &seeds, may_be_separated);
      fresh.build(store, grid, radius, separated, &seeds, may_be_separated);
    }
    else
    {
      kept.build(store, grid, radius, {}, &seeds);
      fresh.build(store, grid, radius, {}, &seeds);
    }
    ASSERT_EQ(kept.n_rows(), fresh.n_rows()) << "step " << step;
    kept_pairs += kept.n_pairs();
    fresh_pairs += fresh.n_pairs();
    if (exchanged)
    {
      EXPECT_EQ(kept.n_list_builds(), searches + 1);
    }
    const std::vector<Point<dim>> &y = store.position;
    std::size_t fresh_within_reach   = 0;
    for (std::size_t p = 0; p < m; ++p)
    {
      ASSERT_EQ(kept.has_row(p), fresh.has_row(p))
          << "step " << step << " particle " << p;
      const double r = with_reaches ? std::min(radius, reach[p]) : radius;
      std::vector<std::uint32_t> within, fresh_within;
      for (auto q = kept.begin(p); q != kept.end(p); ++q)
      {
        // Listed within the reach + skin, and each of the two moved less than half
        // the skin since.
        ASSERT_LE(y[*q].distance(y[p]), r + 2 * skin);
        if (y[*q].distance_square(y[p]) <= r * r)
          within.push_back(*q);
      }
      for (auto q = fresh.begin(p); q != fresh.end(p); ++q)
        if (y[*q].distance_square(y[p]) <= r * r)
          fresh_within.push_back(*q);
      ASSERT_TRUE(std::is_sorted(kept.begin(p), kept.end(p)));
      ASSERT_EQ(within, fresh_within) << "step " << step << " particle " << p;
      fresh_within_reach += fresh_within.size();
      compared += fresh.has_row(p);
      cut_rows += with_crack && fresh.has_row(p) && may_be_separated(p);
    }
    // At the exchange the rows have no skin: exactly the fresh ones cut to the reach.
    if (exchanged)
    {
      EXPECT_EQ(kept.n_pairs(), fresh_within_reach);
    }
    // A smooth drift of at most 0.004 radius per step, and every tenth step a jump of
    // one particle by the skin: the lists must be made anew for each.
    for (std::size_t p = 0; p < m; ++p)
      if (store.body_id[p] != 2)
        for (unsigned int d = 0; d < dim; ++d)
          store.position[p][d] += 0.004 * radius *
                                  std::sin(3 * store.position[p][(d + 1) % dim] + d) /
                                  std::sqrt(dim);
    if (step % 10 == 9)
      store.position[m / 2][0] += skin;
    const std::uint64_t before = store.order_version();
    lme_mpm_test::sort_by_grid_cells(store, grid);
    reorders += store.order_version() != before;
  }
  std::cout << dim << "D: lists made " << kept.n_list_builds() << " times in " << steps
            << " steps, " << reorders << " reorders followed or redone" << std::endl;
  // The drift moves particles across cells: most steps reorder the store.
  EXPECT_GT(reorders, steps / 2);
  EXPECT_GT(compared, steps * m / 20);
  if (with_crack && dim == 2)
  {
    EXPECT_GT(cut_rows, 100u);
  }
  // Made anew for the jumps and the growing patch, but far from every step.
  EXPECT_GE(kept.n_list_builds(), 4u);
  EXPECT_LE(kept.n_list_builds(), steps / 3);
  EXPECT_EQ(fresh.n_list_builds(), steps);
  // Reaches of a half and four fifths of the radius for two thirds of the rows: the
  // kept rows, skin and all, are shorter than the fresh ones.
  if (with_reaches)
  {
    EXPECT_LT(kept_pairs, 0.8 * fresh_pairs);
  }
}
} // namespace

TEST(Neighbourhood, KeptListsGiveTheRowsOfAFreshBuild)
{
  check_kept_lists_against_fresh_builds<2>(false);
  check_kept_lists_against_fresh_builds<3>(false);
}

TEST(Neighbourhood, KeptListsGiveTheRowsOfAFreshBuildAcrossACrack)
{
  check_kept_lists_against_fresh_builds<2>(true);
}

TEST(Neighbourhood, RowsCutToEachParticlesReachAreTheFreshRowsCutToIt)
{
  check_kept_lists_against_fresh_builds<2>(false, true);
  check_kept_lists_against_fresh_builds<3>(false, true);
  check_kept_lists_against_fresh_builds<2>(true, true);
}
