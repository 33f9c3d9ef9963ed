// Unit tests of the local max-ent (LME) shape functions: parameters, supports, Newton
// iterations and warm starts, failures, the SIMD kernels and graded grids.

#include "shape_function_checks.h"

#include "../../source/shape_functions/lme_support.h"

using namespace lme_mpm;
using namespace shape_function_checks;

TEST(ShapeFunctions, LmeParametersAreDeclaredWithDefaults)
{
  ParameterHandler prm;
  prm.enter_subsection("Shape functions");
  ShapeFunctionRegistry<2>::instance().declare_all(prm);
  EXPECT_DOUBLE_EQ(prm.get_double("LME gamma"), 1.8);
  EXPECT_DOUBLE_EQ(prm.get_double("LME tolerance"), 1e-6);
  EXPECT_DOUBLE_EQ(prm.get_double("LME Newton tolerance"), 1e-12);
  EXPECT_EQ(prm.get_integer("LME maximum iterations"), 50);
  EXPECT_ANY_THROW(prm.set("LME gamma", "200"));
  EXPECT_ANY_THROW(prm.set("LME maximum iterations", "0"));
  prm.leave_subsection();
}

TEST(ShapeFunctions, LmeNewtonIterations2D)
{
  for (const double gamma : lme_gammas)
  {
    SCOPED_TRACE("gamma " + std::to_string(gamma));
    check_newton_iterations<2>(gamma, 31);
  }
}

TEST(ShapeFunctions, LmeNewtonIterations3D)
{
  for (const double gamma : lme_gammas)
  {
    SCOPED_TRACE("gamma " + std::to_string(gamma));
    check_newton_iterations<3>(gamma, 32);
  }
}

TEST(ShapeFunctions, LmeWarmStartIsReusedAndStoredInPhysicalUnits)
{
  // The same configuration at two scales: identical N, lambda scales as 1/length.
  auto g1 = uniform_grid<2>(0.1, 10);
  auto g2 = uniform_grid<2>(0.2, 10);
  auto s1 = make<2>("lme", *g1, lme_settings<2>(4.0));
  auto s2 = make<2>("lme", *g2, lme_settings<2>(4.0));
  ParticleStore<2> p1, p2;
  const Point<2> x1(-0.3 + 0.013, 0.1 + 0.437); // near the lower x face
  const Point<2> x2 =
      Point<2>() + 2 * (x1 - g1->lower_corner()) + (g2->lower_corner() - Point<2>());
  add_particle(p1, *g1, x1);
  add_particle(p2, *g2, x2);
  const auto c1 = evaluate(*s1, p1);
  const auto c2 = evaluate(*s2, p2);
  ASSERT_EQ(c1.n_nodes[0], c2.n_nodes[0]);
  for (unsigned int k = 0; k < c1.n_nodes[0]; ++k)
  {
    EXPECT_NEAR(c1.N[k], c2.N[k], 1e-12);
    EXPECT_NEAR((c1.grad_N[k] - 2 * c2.grad_N[k]).norm() * 0.1, 0, 1e-10);
  }
  EXPECT_GT(p1.lme_lambda[0].norm() * 0.1, 1.0); // the boundary pulls lambda up
  EXPECT_NEAR((p1.lme_lambda[0] - 2 * p2.lme_lambda[0]).norm() * 0.1, 0, 1e-9);

  // Recomputing at the same position converges at once from the stored multiplier.
  const double before = lme_iterations(*s1);
  const auto again    = evaluate(*s1, p1);
  EXPECT_EQ(lme_iterations(*s1), before);
  for (unsigned int k = 0; k < c1.n_nodes[0]; ++k)
    EXPECT_NEAR(again.N[k], c1.N[k], 1e-14);
}

/**
 * Small moves take the extrapolated warm start and the linearised Newton step (one
 * exponential pass per solve); the result is the converged max-ent function: it
 * matches a cold solve at the same position to rounding.
 */
TEST(ShapeFunctions, LmeSmallMovesNeedOneExponentialPass)
{
  const double h = 0.1;
  auto grid      = uniform_grid<2>(h, 12);
  for (const double gamma : {1.8, 4.0})
  {
    auto warm_sf = make<2>("lme", *grid, lme_settings<2>(gamma));
    std::mt19937 rng(7);
    ParticleStore<2> moving;
    for (unsigned int i = 0; i < 500; ++i)
      add_particle(moving, *grid, random_point(*grid, rng, 0.05 * h));
    evaluate(*warm_sf, moving);
    // A steady drift of 2e-4 h per step, as in an explicit run.
    std::normal_distribution<double> normal;
    std::vector<Tensor<1, 2>> drift(moving.size());
    for (auto &v : drift)
      v = Tensor<1, 2>({normal(rng), normal(rng)}), v *= 2e-4 * h / v.norm();
    Connectivity<2> warm;
    for (unsigned int step = 0; step < 5; ++step)
    {
      for (std::size_t p = 0; p < moving.size(); ++p)
        moving.position[p] += drift[p];
      const double before = statistic(warm_sf->statistics(), "lme_evaluations");
      warm                = evaluate(*warm_sf, moving);
      const double evaluations =
          statistic(warm_sf->statistics(), "lme_evaluations") - before;
      if (step > 0) // the first move has no motion history to extrapolate from
      {
        EXPECT_LE(evaluations, 1.01 * moving.size()) << "gamma " << gamma;
      }
    }
    ParticleStore<2> fresh;
    for (std::size_t p = 0; p < moving.size(); ++p)
      add_particle(fresh, *grid, moving.position[p]);
    auto cold_sf    = make<2>("lme", *grid, lme_settings<2>(gamma));
    const auto cold = evaluate(*cold_sf, fresh);
    for (std::size_t p = 0; p < moving.size(); ++p)
    {
      ASSERT_EQ(warm.n_nodes[p], cold.n_nodes[p]);
      for (unsigned int k = 0; k < cold.n_nodes[p]; ++k)
      {
        const std::size_t i = p * cold.stride + k;
        EXPECT_NEAR(warm.N[i], cold.N[i], 1e-11);
        EXPECT_NEAR((warm.grad_N[i] - cold.grad_N[i]).norm() * h, 0, 1e-9);
      }
      if (p % 25 == 0)
        expect_consistent(warm, *grid, moving.position[p], p, "lme");
    }
  }
}

namespace
{
/// Largest LME row over many positions (random, on nodes, edges, faces, centres).
template <int dim>
unsigned int largest_lme_row(const ShapeFunction<dim> &sf,
                             const BackgroundGrid<dim> &grid, const unsigned int seed)
{
  std::mt19937 rng(seed);
  ParticleStore<dim> ps;
  const double h = grid.min_spacing();
  for (unsigned int i = 0; i < (dim == 2 ? 5000 : 1500); ++i)
  {
    Point<dim> x = random_point(grid, rng, 3.5 * h);
    if (i % 2 == 0) // snap some coordinates to nodes or cell centres
      for (unsigned int d = 0; d < dim; ++d)
        if (rng() % 2)
        {
          std::array<unsigned int, dim> c;
          grid.locate(x, c);
          x[d] =
              grid.coordinates(d)[c[d]] + (rng() % 2 ? 0.5 * grid.spacing(d, c[d]) : 0);
        }
    add_particle(ps, grid, x);
  }
  const auto conn = evaluate(sf, ps);
  return *std::max_element(conn.n_nodes.begin(), conn.n_nodes.end());
}
} // namespace

TEST(ShapeFunctions, LmeNodeBoundHolds)
{
  for (const double gamma : lme_gammas)
  {
    SCOPED_TRACE("gamma " + std::to_string(gamma));
    auto g2                  = uniform_grid<2>(0.1, 20);
    auto s2                  = make<2>("lme", *g2, lme_settings<2>(gamma));
    const unsigned int most2 = largest_lme_row(*s2, *g2, 91);
    EXPECT_LE(most2, s2->max_nodes_per_particle());
    // Tight enough not to waste the connectivity: within 1.5x of what occurs.
    EXPECT_LE(s2->max_nodes_per_particle(), 1.5 * most2);

    auto g3                  = uniform_grid<3>(0.1, 14);
    auto s3                  = make<3>("lme", *g3, lme_settings<3>(gamma));
    const unsigned int most3 = largest_lme_row(*s3, *g3, 92);
    EXPECT_LE(most3, s3->max_nodes_per_particle());
    EXPECT_LE(s3->max_nodes_per_particle(), 2.0 * most3);
  }
  for_lme_graded_cases<2>(
      [](const BackgroundGrid<2> &g, const double gamma)
      {
        auto sf = make<2>("lme", g, lme_settings<2>(gamma));
        EXPECT_LE(largest_lme_row(*sf, g, 93), sf->max_nodes_per_particle());
      });
  for_lme_graded_cases<3>(
      [](const BackgroundGrid<3> &g, const double gamma)
      {
        auto sf = make<3>("lme", g, lme_settings<3>(gamma));
        EXPECT_LE(largest_lme_row(*sf, g, 94), sf->max_nodes_per_particle());
      });
}

TEST(ShapeFunctions, LmeSupportMatchesRadius)
{
  // Cell centres of a regular grid. The reference README (section 6) quotes 24 / 89
  // nodes for gamma 1.8 as typical; exactly at a cell centre the lattice count within
  // R = 2.77 h is 24 in 2D and 88 in 3D (12 / 32 for gamma 3.5, 4 in 2D for 6.8).
  {
    auto grid = uniform_grid<2>(0.1, 12);
    ParticleStore<2> ps;
    add_particle(ps, *grid, cell_centre<2>(*grid, {{5, 6}}));
    EXPECT_EQ(evaluate(*make<2>("lme", *grid, lme_settings<2>(1.8)), ps).n_nodes[0], 24u);
    EXPECT_EQ(evaluate(*make<2>("lme", *grid, lme_settings<2>(3.5)), ps).n_nodes[0], 12u);
    EXPECT_EQ(evaluate(*make<2>("lme", *grid, lme_settings<2>(6.8)), ps).n_nodes[0], 4u);
  }
  {
    auto grid = uniform_grid<3>(0.1, 10);
    ParticleStore<3> ps;
    add_particle(ps, *grid, cell_centre<3>(*grid, {{4, 5, 4}}));
    EXPECT_EQ(evaluate(*make<3>("lme", *grid, lme_settings<3>(1.8)), ps).n_nodes[0], 88u);
    EXPECT_EQ(evaluate(*make<3>("lme", *grid, lme_settings<3>(3.5)), ps).n_nodes[0], 32u);
  }
  // Anywhere (boundaries, graded cells): exactly the nodes within R, and the bound holds.
  for (const double gamma : lme_gammas)
    check_support_is_ball<2>(*uniform_grid<2>(0.1, 12), gamma, 41);
  for_lme_graded_cases<2>([](const BackgroundGrid<2> &g, const double gamma)
                          { check_support_is_ball<2>(g, gamma, 42); });
  for (const double gamma : lme_gammas)
    check_support_is_ball<3>(*uniform_grid<3>(0.1, 10), gamma, 43);
  for_lme_graded_cases<3>([](const BackgroundGrid<3> &g, const double gamma)
                          { check_support_is_ball<3>(g, gamma, 44); });
}

/// On a graded grid, points on grid lines and one ulp either side of them (where
/// index_box() starts its walks from the cell's bounds): exactly the nodes within R.
template <int dim>
void check_support_on_grid_lines(const BackgroundGrid<dim> &grid, const double gamma,
                                 const unsigned int seed)
{
  std::mt19937 rng(seed);
  ParticleStore<dim> ps;
  const double margin = 1e-3 * grid.min_spacing();
  for (unsigned int i = 0; i < 60; ++i)
  {
    Point<dim> x = random_point(grid, rng, margin);
    // One or two coordinates on a grid line away from the grid's faces.
    for (unsigned int d = 0; d < dim; ++d)
      if (d == i % dim || i % 3 == 0)
      {
        const auto &c = grid.coordinates(d);
        const double line =
            c[1 + std::uniform_int_distribution<std::size_t>(0, c.size() - 3)(rng)];
        const int side = static_cast<int>(i / dim) % 3 - 1; // below, on, above
        x[d] = side == 0 ? line : std::nextafter(line, side < 0 ? -HUGE_VAL : HUGE_VAL);
      }
    add_particle(ps, grid, x);
  }
  expect_supports_are_balls<dim>(grid, gamma, lme_settings<dim>(gamma), ps);
}

TEST(ShapeFunctions, LmeSupportOnGradedGridLinesIsTheBall)
{
  for_lme_graded_cases<2>([](const BackgroundGrid<2> &g, const double gamma)
                          { check_support_on_grid_lines<2>(g, gamma, 45); });
  for_lme_graded_cases<3>([](const BackgroundGrid<3> &g, const double gamma)
                          { check_support_on_grid_lines<3>(g, gamma, 46); });
}

TEST(ShapeFunctions, LmeSupportIsTheBallWhereEveryCellHasItsOwnSpacing)
{
  // A geometric grading: a spacing per cell, too many classes for the weight tables,
  // so index_box() divides per point (the other path of the graded weights).
  BackgroundGrid<2> grid;
  std::array<std::vector<double>, 2> steps;
  for (unsigned int d = 0; d < 2; ++d)
    for (unsigned int i = 0; i < 300; ++i)
      steps[d].push_back(0.01 * std::pow(1.002, i + 150.0 * d));
  grid.reinit(Point<2>(), steps);
  EXPECT_FALSE(shape_functions::LmeSupport<2>(grid, 2.77, 1.8).tables_weights());
  EXPECT_TRUE(
      shape_functions::LmeSupport<2>(*graded_grid<2>(), 2.77, 1.8).tables_weights());
  check_support_is_ball<2>(grid, 1.8, 47);
  check_support_on_grid_lines<2>(grid, 1.8, 48);
}

TEST(ShapeFunctions, LmeIsContinuousAcrossAGradingStep)
{
  // Cells halve in size across x = 0.8 and y = 0.8. Just left and just right of the
  // line x = 0.8 (and below and above y = 0.8) the functions of every node, and their
  // gradients, must agree to the change over the small offset: nodal beta_I is a
  // property of the node, not of the cell the particle is in.
  std::array<std::vector<double>, 2> steps;
  for (auto &s : steps)
  {
    s.assign(8, 0.1);
    s.insert(s.end(), 8, 0.05);
  }
  BackgroundGrid<2> grid;
  grid.reinit(Point<2>(), steps);
  const double delta = 1e-8;
  std::mt19937 rng(61);
  // Along the step, in the coarse cells of the other direction (where the fine cells
  // are 0.05 x 0.1 and every node on the far side is within reach).
  std::uniform_real_distribution<double> u(0.3, 0.75);
  for (const double gamma : {1.8, 3.5})
  {
    SCOPED_TRACE("gamma " + std::to_string(gamma));
    auto sf             = make<2>("lme", grid, lme_settings<2>(gamma, 1e-14));
    double largest_jump = 0, largest_grad_jump = 0;
    for (unsigned int k = 0; k < 40; ++k)
    {
      const unsigned int d = k % 2;
      Point<2> x;
      x[1 - d] = u(rng);
      x[d]     = 0.8;
      ParticleStore<2> ps;
      for (const double side : {-delta, delta})
      {
        Point<2> xs = x;
        xs[d] += side;
        ps.add(xs, 1.0, 1e-3, 0, 0);
      }
      const auto conn = evaluate(*sf, ps);
      // Value and gradient of every node on each side (zero outside the support).
      std::map<unsigned int, std::array<std::pair<double, Tensor<1, 2>>, 2>> at;
      for (unsigned int side = 0; side < 2; ++side)
        for (unsigned int m = 0; m < conn.n_nodes[side]; ++m)
        {
          const std::size_t s     = side * conn.stride + m;
          at[conn.nodes[s]][side] = {conn.N[s], conn.grad_N[s]};
        }
      for (const auto &[node, v] : at)
      {
        largest_jump = std::max(largest_jump, std::abs(v[1].first - v[0].first));
        largest_grad_jump =
            std::max(largest_grad_jump, 0.05 * (v[1].second - v[0].second).norm());
      }
    }
    // A node at its cut-off radius enters with N of order the tolerance 1e-6; a cell's
    // beta would make jumps of order 0.1.
    EXPECT_LT(largest_jump, 1e-5);
    EXPECT_LT(largest_grad_jump, 1e-4);
    std::cout << "gamma " << gamma << ": largest jump of N " << largest_jump
              << ", of h grad N " << largest_grad_jump << std::endl;
  }
}

TEST(ShapeFunctions, LmeFailuresAreLoud)
{
  const double h = 0.1;
  auto grid      = uniform_grid<2>(h, 6);
  const double v = volume_for_half_width<2>(0.25 * h);
  Point<2> near  = grid->lower_corner() + Point<2>(0.1 * h, 0.3);

  // One Newton step is not enough from a cold start near the boundary at gamma 10 ...
  Settings capped                  = lme_settings<2>(10);
  capped["LME maximum iterations"] = "1";
  expect_failure<2>(*make<2>("lme", *grid, capped), near, v);
  // ... but the same solve succeeds with the default cap.
  {
    ParticleStore<2> ps;
    ps.add(near, 1.0, v, 0, 0);
    auto sf = make<2>("lme", *grid, lme_settings<2>(10));
    EXPECT_NO_THROW(evaluate(*sf, ps));
    EXPECT_GT(lme_iterations(*sf), 1.0);
  }
  // On the boundary the multiplier is unbounded (not strictly inside the hull).
  expect_failure<2>(*make<2>("lme", *grid), grid->lower_corner() + Point<2>(0, 0.3), v);
  // A support too small to surround the particle: gamma 100 at a cell centre.
  expect_failure<2>(*make<2>("lme", *grid, lme_settings<2>(100)),
                    cell_centre<2>(*grid, {{2, 3}}), v);
  // Supports that cannot reach across the cell (see graded_grid, lme_settings):
  // 3D gamma 10 with the default cut-off near the centre of a cell face, ...
  {
    auto grid3 = uniform_grid<3>(h, 6);
    Settings s = {{"LME gamma", "10"}};
    expect_failure<3>(*make<3>("lme", *grid3, s),
                      cell_centre<3>(*grid3, {{2, 2, 2}}) + Point<3>(0.49 * h, 0, 0),
                      volume_for_half_width<3>(0.25 * h));
    s["LME tolerance"] = "1e-10";
    ParticleStore<3> ok;
    ok.add(cell_centre<3>(*grid3, {{2, 2, 2}}) + Point<3>(0.49 * h, 0, 0), 1.0, 1e-3, 0,
           0);
    EXPECT_NO_THROW(evaluate(*make<3>("lme", *grid3, s), ok));
  }
  // ... and gamma 6.8 in a cell of aspect ratio 2.2, near its short edge: the nodes on
  // the far side (0.1 away) have h_I = 0.055 (their spacing along y) and reach only
  // 1.43 h_I = 0.079.
  {
    auto graded = graded_grid<2>();
    // Cell (12, 0): spacings 0.11 x 0.05.
    const Point<2> x(graded->coordinates(0)[12] + 0.01, 0.025);
    EXPECT_NEAR(graded->spacing(0, 12) / graded->spacing(1, 0), 2.2, 1e-12);
    expect_failure<2>(*make<2>("lme", *graded, lme_settings<2>(6.8)), x, v);
    ParticleStore<2> ok;
    ok.add(x, 1.0, v, 0, 0);
    EXPECT_NO_THROW(evaluate(*make<2>("lme", *graded, lme_settings<2>(1.8)), ok));
  }
  // The message carries the family, the particle id and a reason.
  ParticleStore<2> ps;
  ps.add(grid->lower_corner() + Point<2>(0.3, 0.3), 1.0, v, 0, 0);
  ps.add(grid->lower_corner() + Point<2>(0, 0.3), 1.0, v, 0, 0);
  Connectivity<2> conn;
  auto sf = make<2>("lme", *grid);
  conn.resize(2, sf->max_nodes_per_particle());
  try
  {
    sf->compute(ps, 0, 2, conn);
    ADD_FAILURE() << "no exception";
  }
  catch (const ExcShapeFunctionFailure &e)
  {
    const std::string what = e.what();
    EXPECT_NE(what.find("lme shape functions failed at particle 1"), std::string::npos)
        << what;
    EXPECT_NE(what.find("convex hull"), std::string::npos) << what;
  }
}

namespace
{
template <int dim>
void time_lme(const BackgroundGrid<dim> &grid, const double h, const std::size_t n,
              const std::string &label)
{
  auto sf = make<dim>("lme", grid, lme_settings<dim>(1.8));
  std::mt19937 rng(81);
  ParticleStore<dim> ps;
  for (std::size_t i = 0; i < n; ++i)
    ps.add(random_point(grid, rng, 0.01 * h), 1.0, std::pow(h, dim) / (1 << dim), 0, 0);
  Connectivity<dim> conn;
  conn.resize(ps.size(), sf->max_nodes_per_particle());
  using clock = std::chrono::steady_clock;
  auto t0     = clock::now();
  sf->compute(ps, 0, ps.size(), conn);
  const double cold =
      std::chrono::duration<double, std::nano>(clock::now() - t0).count() / n;
  const double it_cold = lme_iterations(*sf);
  std::normal_distribution<double> normal;
  for (std::size_t p = 0; p < n; ++p)
    for (unsigned int d = 0; d < dim; ++d)
      ps.position[p][d] = std::clamp(ps.position[p][d] + 1e-3 * h * normal(rng),
                                     grid.lower_corner()[d] + 1e-4 * h,
                                     grid.upper_corner()[d] - 1e-4 * h);
  t0 = clock::now();
  sf->compute(ps, 0, ps.size(), conn);
  const double warm =
      std::chrono::duration<double, std::nano>(clock::now() - t0).count() / n;
  std::cout << label << ": cold " << cold << " ns/particle (" << it_cold / n
            << " iterations), warm " << warm << " ns/particle ("
            << (lme_iterations(*sf) - it_cold) / n << " iterations), "
            << sf->max_nodes_per_particle() << " max nodes" << std::endl;
}
} // namespace

// Timing, not a check: run with --gtest_also_run_disabled_tests.
TEST(ShapeFunctions, DISABLED_LmeTiming)
{
  auto g2 = uniform_grid<2>(0.01, 160);
  time_lme<2>(*g2, 0.01, 100000, "2D gamma 1.8, 100k particles");
  auto g3 = uniform_grid<3>(0.02, 30);
  time_lme<3>(*g3, 0.02, 20000, "3D gamma 1.8, 20k particles");
}

// The 2D LME passes in AVX2 and in scalar code give the same shape functions to
// rounding, on a uniform and a graded grid, for a smooth and a local gamma, from a
// cold start and after a small move (the polynomial steps).
TEST(ShapeFunctions, LmeKernelsAgreeToRounding)
{
  // Without AVX2 'auto' is the scalar passes too, and the comparison says nothing.
  if (!shape_functions::lme_simd::avx2_kernels())
    GTEST_SKIP() << "the processor has no AVX2 with FMA";
  std::mt19937 rng(11);
  for (const bool graded : {false, true})
    for (const char *gamma : {"1.8", "6.8"})
    {
      if (graded && std::string(gamma) != "1.8")
        continue; // the strongly graded grid takes gamma <= 1.8 (above)
      const auto grid   = graded ? graded_grid<2>() : uniform_grid<2>(0.1, 12);
      const Point<2> lo = grid->lower_corner(), hi = grid->upper_corner();
      ParticleStore<2> particles;
      std::uniform_real_distribution<double> u(0.0, 1.0);
      for (unsigned int k = 0; k < 400; ++k)
      {
        Point<2> x;
        for (unsigned int d = 0; d < 2; ++d)
          x[d] = lo[d] + (0.1 + 0.8 * u(rng)) * (hi[d] - lo[d]);
        add_particle(particles, *grid, x);
      }
      ParticleStore<2> moved;
      const auto scalar =
          make<2>("lme", *grid, {{"LME gamma", gamma}, {"LME kernel", "scalar"}});
      const auto simd =
          make<2>("lme", *grid, {{"LME gamma", gamma}, {"LME kernel", "auto"}});
      for (unsigned int pass = 0; pass < 2; ++pass)
      {
        if (pass == 1) // a small move: warm starts and polynomial steps
          for (auto &x : particles.position)
            x[0] += 1e-4, x[1] -= 2e-4;
        moved = particles; // the same warm start for both

        const Connectivity<2> a = evaluate(*scalar, particles);
        const Connectivity<2> b = evaluate(*simd, moved);
        for (std::size_t p = 0; p < particles.size(); ++p)
        {
          ASSERT_EQ(a.n_nodes[p], b.n_nodes[p]);
          for (unsigned int k = 0; k < a.n_nodes[p]; ++k)
          {
            const std::size_t i = p * a.stride + k, j = p * b.stride + k;
            ASSERT_EQ(a.nodes[i], b.nodes[j]);
            EXPECT_NEAR(a.N[i], b.N[j], 1e-13) << "particle " << p << ", gamma " << gamma;
            EXPECT_NEAR(a.grad_N[i][0], b.grad_N[j][0], 1e-11);
            EXPECT_NEAR(a.grad_N[i][1], b.grad_N[j][1], 1e-11);
          }
        }
      }
    }
}

// The connectivity's rows on graded grids: sized by the most nodes that reach a cell
// (every particle fits), and in 2D not much more than the most any point has, where
// the ball bound with the widest support and the narrowest spacing was about three
// times that (and the transfers read rows that were mostly empty).
template <int dim>
void check_lme_rows_fit_graded_grid(const BackgroundGrid<dim> &grid,
                                    const unsigned int n_points)
{
  const auto lme = make<dim>("lme", grid);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Point<dim> lo = grid.lower_corner(), hi = grid.upper_corner();
  ParticleStore<dim> particles;
  for (unsigned int k = 0; k < n_points; ++k)
  {
    Point<dim> x;
    for (unsigned int d = 0; d < dim; ++d)
      x[d] = lo[d] + (0.15 + 0.7 * u(rng)) * (hi[d] - lo[d]);
    add_particle(particles, grid, x);
  }
  const Connectivity<dim> conn = evaluate(*lme, particles); // stops if a row overflows
  const unsigned int most = *std::max_element(conn.n_nodes.begin(), conn.n_nodes.end());
  EXPECT_LE(most, lme->max_nodes_per_particle());
  // In 3D a cell widens the ball by more (about twice the most at a point here).
  if (dim == 2)
  {
    EXPECT_LE(lme->max_nodes_per_particle(), most + most / 4 + 4)
        << "most nodes at a point " << most;
  }
}

TEST(ShapeFunctions, LmeRowsFitGradedGridsTightly)
{
  // The drop-weight scene's middle: 1.25 mm columns between 2.5 mm ones, 1.25 mm rows
  // between 2.5 mm ones (cells at most twice as long as wide).
  BackgroundGrid<2> grid;
  std::array<std::vector<double>, 2> steps;
  for (const auto &[n, h] : {std::pair{8, 0.0025}, {24, 0.00125}, {8, 0.0025}})
    steps[0].insert(steps[0].end(), n, h);
  for (const auto &[n, h] : {std::pair{16, 0.0025}, {8, 0.00125}, {12, 0.0025}})
    steps[1].insert(steps[1].end(), n, h);
  grid.reinit(Point<2>(), steps);
  check_lme_rows_fit_graded_grid<2>(grid, 20000);
  check_lme_rows_fit_graded_grid<2>(*graded_grid<2>(), 5000);
  check_lme_rows_fit_graded_grid<3>(*graded_grid<3>(), 3000);
}
