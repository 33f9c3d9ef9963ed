// Grid, particle store, scatter determinism and the verification scenes.
#include <deal.II/base/multithread_info.h>

#include <gtest/gtest.h>

#include <lme_mpm/grid/background_grid.h>
#include <lme_mpm/particles/particle_store.h>

#include "test_helpers.h"

#include <cmath>
#include <random>

using namespace lme_mpm;

TEST(BackgroundGrid, LexicographicNodesMatchDealIIVertices)
{
  BackgroundGrid<2> grid;
  grid.reinit(Point<2>(-1, 0), {{std::vector<double>(4, 0.5), {0.1, 0.2, 0.3}}});
  EXPECT_EQ(grid.n_nodes(), 5u * 4u);
  EXPECT_EQ(grid.n_cells(), 12u);
  EXPECT_FALSE(grid.is_uniform(1));
  // Every deal.II vertex DoF sits at the lexicographic node's position.
  for (const auto &cell : grid.dof_handler().active_cell_iterators())
    for (const unsigned int v : cell->vertex_indices())
    {
      const Point<2> p = cell->vertex(v);
      std::array<unsigned int, 2> ijk;
      ASSERT_TRUE(grid.locate(p, ijk));
      bool found = false;
      for (unsigned int n = 0; n < grid.n_nodes(); ++n)
        if (grid.node_point(n).distance(p) < 1e-12)
        {
          found = true;
          EXPECT_EQ(grid.dof(n, 0), cell->vertex_dof_index(v, 0));
          EXPECT_EQ(grid.dof(n, 1), cell->vertex_dof_index(v, 1));
        }
      EXPECT_TRUE(found);
    }
}

TEST(BackgroundGrid, LocateUniformAndGraded)
{
  BackgroundGrid<2> grid;
  grid.reinit(Point<2>(0, 0), {{std::vector<double>(10, 0.1), {0.1, 0.1, 0.2, 0.4}}});
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> ux(0, 1), uy(0, 0.8);
  for (int i = 0; i < 1000; ++i)
  {
    const Point<2> x(ux(rng), uy(rng));
    std::array<unsigned int, 2> ijk;
    ASSERT_TRUE(grid.locate(x, ijk));
    for (unsigned int d = 0; d < 2; ++d)
    {
      EXPECT_LE(grid.coordinates(d)[ijk[d]], x[d]);
      EXPECT_GE(grid.coordinates(d)[ijk[d] + 1], x[d]);
    }
  }
  std::array<unsigned int, 2> ijk;
  EXPECT_FALSE(grid.locate(Point<2>(-1e-9, 0.5), ijk));
  EXPECT_FALSE(grid.locate(Point<2>(0.5, 0.80001), ijk));
  EXPECT_TRUE(grid.locate(Point<2>(1.0, 0.8), ijk));
  EXPECT_EQ(ijk[0], 9u);
  EXPECT_EQ(ijk[1], 3u);
  EXPECT_EQ(grid.nodes_on_boundary(0).size(), 5u);
  EXPECT_EQ(grid.nodes_on_boundary(3).size(), 11u);
}

TEST(ParticleStore, CountingSortKeepsFieldsTogether)
{
  ParticleStore<2> store;
  std::mt19937 rng(7);
  for (unsigned int p = 0; p < 500; ++p)
  {
    store.add(Point<2>(p, 0), p + 1.0, 1.0, 0, 0);
    store.cell[p] = rng() % 37;
  }
  EXPECT_TRUE(store.sort_by_cell(37));
  for (std::size_t p = 0; p < store.size(); ++p)
  {
    if (p > 0)
    {
      EXPECT_LE(store.cell[p - 1], store.cell[p]);
      if (store.cell[p - 1] == store.cell[p]) // stable
        EXPECT_LT(store.id[p - 1], store.id[p]);
    }
    EXPECT_EQ(store.mass[p], store.id[p] + 1.0);
    EXPECT_EQ(store.position[p][0], double(store.id[p]));
  }
  const auto &off = store.cell_offsets();
  for (unsigned int c = 0; c < 37; ++c)
    for (std::size_t p = off[c]; p < off[c + 1]; ++p)
      EXPECT_EQ(store.cell[p], c);
  EXPECT_FALSE(store.sort_by_cell(37)); // already sorted: no reorder
}

namespace
{
/// Positions and velocities after a short two-disc run with a thread limit.
std::vector<double> disc_state(const unsigned int threads)
{
  MultithreadInfo::set_thread_limit(threads);
  ParameterHandler prm;
  ParameterCounts counts;
  counts.bodies = 2;
  Simulation<2>::declare_parameters(prm, counts);
  prm.parse_input(lme_mpm_test::scene("two_disk_collision.prm"));
  apply_overrides(prm,
                  {"Output/Verbosity=0", "Time/End time=1.3",
                   "Output/Directory=" + lme_mpm_test::scratch("threads")},
                  false);
  std::ostringstream quiet;
  Simulation<2> sim(prm, counts, quiet);
  sim.run();
  std::vector<double> state;
  for (std::size_t p = 0; p < sim.particles().size(); ++p)
    for (unsigned int d = 0; d < 2; ++d)
      state.push_back(sim.particles().position[p][d]),
          state.push_back(sim.particles().velocity[p][d]);
  MultithreadInfo::set_thread_limit();
  return state;
}
} // namespace

TEST(Threads, ResultsBitwiseIndependentOfThreadCount)
{
  const auto one = disc_state(1), two = disc_state(2);
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t i = 0; i < one.size(); ++i)
    ASSERT_EQ(one[i], two[i]) << "entry " << i;
}

TEST(VibratingBar, LinearErrorBoundAndConvergence)
{
  // Acceptance: error at most 0.02, falling by at least 1.5x per halving of h.
  std::vector<double> errors;
  for (const char *h : {"0.05", "0.025", "0.0125"})
  {
    const auto r = lme_mpm_test::run_scene(
        "vibrating_bar.prm", "bar",
        {std::string("Grid/Cell size=") + h, "Output/Write particle files=false"});
    errors.push_back(r.at("max_error_displacement_l2"));
    EXPECT_LT(r.at("max_energy_drift"), 1e-3);
  }
  for (std::size_t i = 0; i < errors.size(); ++i)
    EXPECT_LE(errors[i], 0.02) << "level " << i;
  for (std::size_t i = 1; i < errors.size(); ++i)
    EXPECT_GE(errors[i - 1] / errors[i], 1.5) << "levels " << i - 1 << ", " << i;
  // Observed order (printed for the record): about 2 for this smooth, small-strain case.
  std::cout << "vibrating bar (linear): errors " << errors[0] << " " << errors[1] << " "
            << errors[2] << ", order " << std::log2(errors[1] / errors[2]) << std::endl;
}

TEST(TwoDiscCollision, EnergyConservedAndDiscsBounceApart)
{
  ParameterHandler prm;
  ParameterCounts counts;
  counts.bodies = 2;
  Simulation<2>::declare_parameters(prm, counts);
  prm.parse_input(lme_mpm_test::scene("two_disk_collision.prm"));
  apply_overrides(prm,
                  {"Output/Verbosity=0", "Output/Write particle files=false",
                   "Output/Directory=" + lme_mpm_test::scratch("discs")},
                  false);
  std::ostringstream quiet;
  Simulation<2> sim(prm, counts, quiet);
  const auto summary = sim.run();
  EXPECT_LT(summary.at("max_energy_drift"), 0.03);
  std::cout << "two discs (scene default shape functions): max energy drift "
            << summary.at("max_energy_drift") << std::endl;
  // Momentum of each disc after the impact: they move apart along the diagonal.
  Tensor<1, 2> momentum[2];
  for (std::size_t p = 0; p < sim.particles().size(); ++p)
    momentum[sim.particles().body_id[p]] +=
        sim.particles().mass[p] * sim.particles().velocity[p];
  EXPECT_LT(momentum[0][0], 0);
  EXPECT_LT(momentum[0][1], 0);
  EXPECT_GT(momentum[1][0], 0);
  EXPECT_GT(momentum[1][1], 0);
  // Total momentum stays zero (equal and opposite discs).
  EXPECT_LT((momentum[0] + momentum[1]).norm(), 1e-9 * momentum[0].norm());
}

TEST(VibratingBar, LmeBeatsLinearAndConvergesAtSecondOrder)
{
  // Acceptance (issue 3): LME gamma = 1.8 has a lower error than linear on the same
  // grid and an observed order of at least 1.8 over three refinements.
  std::vector<double> lme, linear;
  for (const char *h : {"0.05", "0.025", "0.0125", "0.00625"})
    for (const char *type : {"lme", "linear"})
    {
      const auto r = lme_mpm_test::run_scene(
          "vibrating_bar.prm", std::string("bar_") + type,
          {std::string("Grid/Cell size=") + h,
           std::string("Shape functions/Type=") + type, "Shape functions/LME gamma=1.8",
           "Output/Write particle files=false"});
      (std::string(type) == "lme" ? lme : linear)
          .push_back(r.at("max_error_displacement_l2"));
    }
  for (std::size_t i = 0; i < lme.size(); ++i)
  {
    EXPECT_LT(lme[i], linear[i]) << "level " << i;
    if (i > 0)
    {
      const double order = std::log2(lme[i - 1] / lme[i]);
      std::cout << "LME order between levels " << i - 1 << " and " << i << ": " << order
                << std::endl;
      EXPECT_GE(order, 1.8) << "levels " << i - 1 << ", " << i;
    }
  }
}
