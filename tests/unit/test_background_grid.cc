// BackgroundGrid: nodes, cells and location on uniform and graded grids.
#include <deal.II/base/multithread_info.h>

#include <gtest/gtest.h>

#include <lme_mpm/grid/background_grid.h>
#include <lme_mpm/output/particle_output.h>
#include <lme_mpm/output/probes.h>
#include <lme_mpm/particles/particle_store.h>

#include "test_helpers.h"

#include <cmath>
#include <filesystem>
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
