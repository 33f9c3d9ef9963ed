// Unit tests every shape-function family (linear, ugimp, bspline, lme) passes: the
// consistency conditions every MPM transfer relies on, gradients against finite
// differences, the node-support bounds, boundaries, threads and the crack band.

#include "shape_function_checks.h"

using namespace lme_mpm;
using namespace shape_function_checks;

TEST(ShapeFunctions, RegistryHasAllFamilies)
{
  auto g2 = uniform_grid<2>(0.1, 6);
  auto g3 = uniform_grid<3>(0.1, 6);
  for (const auto &type : all_types)
  {
    EXPECT_TRUE(ShapeFunctionRegistry<2>::instance().contains(type)) << type;
    EXPECT_TRUE(ShapeFunctionRegistry<3>::instance().contains(type)) << type;
    EXPECT_EQ(make<2>(type, *g2)->name(), type);
    EXPECT_EQ(make<3>(type, *g3)->name(), type);
  }
}

TEST(ShapeFunctions, ConsistencyUniform2D)
{
  auto grid = uniform_grid<2>(0.1, 12);
  for (const std::string type : {"linear", "ugimp", "bspline"})
    check_random_particles<2>(type, *grid, {}, 300, 1);
  for (const double gamma : lme_gammas)
    check_random_particles<2>("lme", *grid, lme_settings<2>(gamma), 300, 2);
}

TEST(ShapeFunctions, ConsistencyUniform3D)
{
  auto grid = uniform_grid<3>(0.1, 10);
  for (const std::string type : {"linear", "ugimp", "bspline"})
    check_random_particles<3>(type, *grid, {}, 200, 3);
  for (const double gamma : lme_gammas)
    check_random_particles<3>("lme", *grid, lme_settings<3>(gamma), 100, 4);
}

/**
 * The bound a distributed run's halo is built from: every node a particle couples to
 * lies within that node's node_support_radius(), itself within support_radius(), for
 * every family on a uniform and a graded grid; and where the graded grid is fine LME's
 * bound is the node's own (shorter than the grid-wide one).
 */
template <int dim>
void check_node_support_bounds(const unsigned int seed)
{
  std::mt19937 rng(seed);
  auto uniform = uniform_grid<dim>(0.1, 8);
  auto graded  = graded_grid<dim>();
  for (const auto *grid : {uniform.get(), graded.get()})
    for (const auto &type : all_types)
    {
      if (type == "bspline" && grid == graded.get())
        continue; // uniform grids only
      SCOPED_TRACE(type + (grid == graded.get() ? " graded" : " uniform"));
      auto sf =
          make<dim>(type, *grid, type == "lme" ? lme_settings<dim>(1.8) : Settings{});
      ParticleStore<dim> ps;
      for (unsigned int i = 0; i < 40; ++i)
        add_particle(ps, *grid, random_point(*grid, rng, 1e-3 * grid->min_spacing()));
      const auto conn     = evaluate(*sf, ps);
      const double global = sf->support_radius(*grid);
      for (std::size_t p = 0; p < ps.size(); ++p)
        for (unsigned int k = 0; k < conn.n_nodes[p]; ++k)
        {
          const unsigned int node = conn.nodes[p * conn.stride + k];
          std::array<unsigned int, dim> ijk;
          for (unsigned int d = 0, rest = node; d < dim; ++d)
            ijk[d] = rest % grid->n_nodes_in(d), rest /= grid->n_nodes_in(d);
          const double r = sf->node_support_radius(*grid, ijk);
          EXPECT_LE(grid->node_point(node).distance(ps.position[p]), r * (1 + 1e-12));
          EXPECT_LE(r, global * (1 + 1e-12));
        }
      if (type == "lme" && grid == graded.get())
      {
        // A node among the 0.05 cells of direction 0 (index 6).
        std::array<unsigned int, dim> fine;
        fine.fill(6);
        EXPECT_LT(sf->node_support_radius(*grid, fine), 0.75 * global);
      }
    }
}

TEST(ShapeFunctions, NodeSupportRadiiBoundTheSupports2D)
{
  check_node_support_bounds<2>(11);
}

TEST(ShapeFunctions, NodeSupportRadiiBoundTheSupports3D)
{
  check_node_support_bounds<3>(12);
}

TEST(ShapeFunctions, ConsistencyGraded2D)
{
  auto grid = graded_grid<2>();
  for (const std::string type : {"linear", "ugimp"})
    check_random_particles<2>(type, *grid, {}, 300, 5);
  for_lme_graded_cases<2>(
      [](const BackgroundGrid<2> &g, const double gamma)
      { check_random_particles<2>("lme", g, lme_settings<2>(gamma), 300, 6); });
}

TEST(ShapeFunctions, ConsistencyGraded3D)
{
  auto grid = graded_grid<3>();
  for (const std::string type : {"linear", "ugimp"})
    check_random_particles<3>(type, *grid, {}, 200, 7);
  for_lme_graded_cases<3>(
      [](const BackgroundGrid<3> &g, const double gamma)
      { check_random_particles<3>("lme", g, lme_settings<3>(gamma), 100, 8); });
}

/**
 * Gradients of every family on a uniform grid of @p n_cells cells per direction and
 * on a graded grid, at @p n_particles random particles (half as many for LME), with
 * random seeds seed, seed + 1, ...
 */
template <int dim>
void check_all_gradients(const unsigned int n_cells, const unsigned int n_particles,
                         const unsigned int seed)
{
  auto uniform = uniform_grid<dim>(0.1, n_cells);
  auto graded  = graded_grid<dim>();
  for (const std::string type : {"linear", "ugimp", "bspline"})
    check_gradients<dim>(type, *uniform, {}, n_particles, seed);
  for (const std::string type : {"linear", "ugimp"})
    check_gradients<dim>(type, *graded, {}, n_particles, seed + 1);
  // A tighter Newton tolerance: the multiplier's error enters the differences / delta.
  for (const double gamma : lme_gammas)
    check_gradients<dim>("lme", *uniform, lme_settings<dim>(gamma, 1e-14),
                         n_particles / 2, seed + 2);
  for_lme_graded_cases<dim>(
      [&](const BackgroundGrid<dim> &g, const double gamma)
      {
        check_gradients<dim>("lme", g, lme_settings<dim>(gamma, 1e-14), n_particles / 2,
                             seed + 3);
      });
}

TEST(ShapeFunctions, GradientsMatchFiniteDifferences2D)
{
  check_all_gradients<2>(12, 40, 11);
}

TEST(ShapeFunctions, GradientsMatchFiniteDifferences3D)
{
  check_all_gradients<3>(8, 20, 21);
}

TEST(ShapeFunctions, NearBoundary)
{
  for (const std::string type : {"linear", "ugimp", "bspline"})
  {
    check_near_boundary<2>(type, {});
    check_near_boundary<3>(type, {});
  }
  for (const double gamma : lme_gammas)
  {
    check_near_boundary<2>("lme", lme_settings<2>(gamma));
    check_near_boundary<3>("lme", lme_settings<3>(gamma));
  }
}

TEST(ShapeFunctions, BoundaryInterpolation)
{
  // At a grid corner every family but uGIMP interpolates: the corner node gets 1.
  auto grid = uniform_grid<2>(0.1, 6);
  for (const std::string type : {"linear", "bspline"})
  {
    ParticleStore<2> ps;
    add_particle(ps, *grid, grid->lower_corner());
    const auto conn = evaluate(*make<2>(type, *grid), ps);
    EXPECT_EQ(conn.nodes[0], 0u);
    EXPECT_NEAR(conn.N[0], 1.0, 1e-15) << type;
  }
  // B-spline interior weights at a node: 1/6, 2/3, 1/6 per direction.
  ParticleStore<2> ps;
  add_particle(ps, *grid, grid->node_point(grid->node_index({{3, 2}})));
  const auto conn               = evaluate(*make<2>("bspline", *grid), ps);
  const std::array<double, 4> w = {{1. / 6, 2. / 3, 1. / 6, 0}};
  ASSERT_EQ(conn.n_nodes[0], 16u);
  for (unsigned int b = 0; b < 4; ++b)
    for (unsigned int a = 0; a < 4; ++a)
    {
      EXPECT_EQ(conn.nodes[4 * b + a], grid->node_index({{2 + a, 1 + b}}));
      EXPECT_NEAR(conn.N[4 * b + a], w[a] * w[b], 1e-15);
    }
}

TEST(ShapeFunctions, ConcurrentRangesMatchSerial)
{
  auto grid = uniform_grid<2>(0.1, 12);
  std::mt19937 rng(71);
  ParticleStore<2> serial;
  for (unsigned int i = 0; i < 400; ++i)
    add_particle(serial, *grid, random_point(*grid, rng, 0.3));
  for (const auto &type : all_types)
  {
    auto sf                   = make<2>(type, *grid);
    ParticleStore<2> parallel = serial;
    const auto expected       = evaluate(*sf, serial);
    Connectivity<2> conn;
    conn.resize(parallel.size(), sf->max_nodes_per_particle());
    std::thread t1([&] { sf->compute(parallel, 0, 150, conn); });
    std::thread t2([&] { sf->compute(parallel, 150, parallel.size(), conn); });
    t1.join(), t2.join();
    EXPECT_EQ(conn.n_nodes, expected.n_nodes) << type;
    EXPECT_EQ(conn.nodes, expected.nodes) << type;
    EXPECT_EQ(conn.N, expected.N) << type;
    if (type == "lme")
    {
      EXPECT_EQ(statistic(sf->statistics(), "lme_solves"), 2.0 * serial.size());
    }
  }
}

TEST(ShapeFunctions, ParticleOutsideGridThrows)
{
  const double h = 0.1;
  auto g2        = uniform_grid<2>(h, 6);
  auto g3        = uniform_grid<3>(h, 6);
  for (const auto &type : all_types)
  {
    auto s2 = make<2>(type, *g2);
    auto s3 = make<3>(type, *g3);
    Point<2> below2(g2->lower_corner()[0] - 0.01 * h, g2->lower_corner()[1] + 0.3);
    Point<2> above2(g2->lower_corner()[0] + 0.3, g2->upper_corner()[1] + 1e-9);
    Point<3> below3 = g3->lower_corner() + Point<3>(0.3, 0.3, -0.01 * h);
    const auto v2   = volume_for_half_width<2>(0.1 * h),
               v3   = volume_for_half_width<3>(0.1 * h);
    expect_failure<2>(*s2, below2, v2);
    expect_failure<2>(*s2, above2, v2);
    expect_failure<3>(*s3, below3, v3);
  }
}

TEST(ShapeFunctions, CrackBandFollowsTheStepResponse)
{
  // A nodal jump strains particle columns by the functions' step response g; the band
  // width is 1 / (h max g) and the reach how far from the most strained columns g stays
  // above 1 % of its peak. Exact values at two Gauss points per cell (offsets
  // 1/2 -+ 1/(2 sqrt 3)) and at two midpoints (1/4, 3/4): linear g = 1/h on its cell;
  // cubic B-splines: g is the quadratic B-spline B2 about the jump's cell centre,
  // B2(t) = 3/4 - t^2, (3/2 - |t|)^2 / 2; uGIMP (particle half the cell): the share
  // of the particle's domain inside the cell over its width. LME: an independent
  // Newton solve of the max-ent functions on the same lattice (no cut-off).
  const double h = 0.01, s3 = 1 / std::sqrt(3.0);
  const auto grid                 = uniform_grid<2>(h, 12);
  const std::vector<double> gauss = {0.5 - 0.5 * s3, 0.5 + 0.5 * s3}, half = {0.5, 0.5},
                            mid = {0.25, 0.75};
  const double thickness        = 0.02;
  const auto band = [&](const std::string &type, const std::vector<double> &offsets,
                        const Settings &settings = {})
  {
    const auto sf = make<2>(type, *grid, settings, thickness);
    return crack_band<2>(*sf, *grid, offsets, half, thickness);
  };
  const auto linear = band("linear", gauss);
  EXPECT_NEAR(linear.width_cells, 1.0, 1e-12);
  EXPECT_EQ(linear.reach_cells, 0.0);
  EXPECT_NEAR(band("linear", mid).width_cells, 1.0, 1e-12);

  const auto bspline = band("bspline", gauss);
  EXPECT_NEAR(bspline.width_cells, 1 / (0.75 - 1.0 / 12), 1e-10); // 1.5
  EXPECT_NEAR(bspline.reach_cells, 1.0, 1e-10); // B2 at 1.29: 3.3 % of the peak
  EXPECT_NEAR(band("bspline", mid).width_cells, 1 / 0.6875, 1e-10);

  const auto ugimp = band("ugimp", gauss);
  EXPECT_NEAR(ugimp.width_cells, 1 / (1.5 - s3), 1e-10); // 1.0839
  // The neighbouring cell's nearer column (at -(1/2 - 1/(2 sqrt 3)) h) keeps 7.7 %.
  EXPECT_NEAR(ugimp.reach_cells, 1 - s3, 1e-10);

  const auto lme18 = band("lme", gauss, {{"LME gamma", "1.8"}});
  EXPECT_NEAR(lme18.width_cells, 1.32046, 1e-3);
  EXPECT_NEAR(lme18.reach_cells, 1.0, 1e-10); // 2.8 % one cell on, 0.08 % two
  const auto lme35 = band("lme", gauss, {{"LME gamma", "3.5"}});
  EXPECT_NEAR(lme35.width_cells, 1.01936, 1e-3);
  EXPECT_NEAR(lme35.reach_cells, 1 - s3, 1e-10); // 1.3 % there, 0.07 % one cell on
}
