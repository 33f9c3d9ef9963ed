// BackgroundGrid: nodes, cells and location on uniform and graded grids.
#include <deal.II/base/multithread_info.h>

#include <gtest/gtest.h>

#include <lme_mpm/grid/background_grid.h>
#include <lme_mpm/output/particle_output.h>
#include <lme_mpm/output/probes.h>
#include <lme_mpm/particles/particle_store.h>

#include "test_helpers.h"

#include <algorithm>
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

// The graded lookup (buckets of the smallest spacing) against a binary search of the
// coordinates, at every node, just either side of it, and at random points, on steps
// of very different sizes: the same cell everywhere, faces to the upper cell.
TEST(BackgroundGrid, GradedLocateMatchesBinarySearchAtEveryFace)
{
  BackgroundGrid<2> grid;
  const std::vector<double> steps = {0.3, 0.07, 0.011, 0.011, 0.5, 0.013, 0.2, 0.0999};
  grid.reinit(Point<2>(-0.37, 0), {{steps, std::vector<double>(3, 0.25)}});
  ASSERT_FALSE(grid.is_uniform(0));
  const auto &c        = grid.coordinates(0);
  const auto reference = [&](const double x)
  {
    const long k =
        static_cast<long>(std::upper_bound(c.begin(), c.end(), x) - c.begin()) - 1;
    return static_cast<unsigned int>(std::clamp<long>(k, 0, c.size() - 2));
  };
  std::vector<double> xs;
  for (const double ci : c)
    for (const double x : {std::nextafter(ci, -1e9), ci, std::nextafter(ci, 1e9)})
      if (x >= c.front() && x <= c.back())
        xs.push_back(x);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(c.front(), c.back());
  for (int i = 0; i < 10000; ++i)
    xs.push_back(u(rng));
  for (const double x : xs)
  {
    unsigned int i = 12345;
    ASSERT_TRUE(grid.locate(x, 0, i));
    EXPECT_EQ(i, reference(x)) << "x = " << x;
  }
}

// locate() from a cell found before: the answer of the search whatever the cell given
// (the right one, a neighbour along x or y, any other, one out of range), at every face
// and corner of a graded and a uniform grid and at random points, and false outside the
// grid.
TEST(BackgroundGrid, LocateFromACellGivesTheSearchsCell)
{
  for (const bool graded : {true, false})
  {
    BackgroundGrid<2> grid;
    const std::vector<double> steps =
        graded ? std::vector<double>{0.3, 0.07, 0.011, 0.011, 0.5, 0.013, 0.2, 0.0999}
               : std::vector<double>(8, 0.1);
    grid.reinit(Point<2>(-0.37, 0.1), {{steps, std::vector<double>(3, 0.25)}});
    ASSERT_EQ(grid.is_uniform(0), !graded);
    std::vector<std::vector<double>> xs(2);
    std::mt19937 rng(11);
    for (unsigned int d = 0; d < 2; ++d)
    {
      const auto &c = grid.coordinates(d);
      for (const double ci : c)
        for (const double x : {std::nextafter(ci, -1e9), ci, std::nextafter(ci, 1e9)})
          xs[d].push_back(x);
      std::uniform_real_distribution<double> u(c.front(), c.back());
      for (int i = 0; i < 60; ++i)
        xs[d].push_back(u(rng));
    }
    std::uniform_int_distribution<unsigned int> any_cell(0, grid.n_cells() + 3);
    std::size_t hits = 0;
    for (const double x : xs[0])
      for (const double y : xs[1])
      {
        const Point<2> p(x, y);
        std::array<unsigned int, 2> expected, found;
        const bool inside               = grid.locate(p, expected);
        std::vector<unsigned int> hints = {any_cell(rng), grid.n_cells(), ~0u};
        if (inside)
        {
          const unsigned int own = grid.cell_index(expected);
          hints.push_back(own);
          // The neighbours along x and y: the cells a point on a face might be put in.
          for (unsigned int d = 0; d < 2; ++d)
          {
            const unsigned int stride = d == 0 ? 1 : grid.n_cells_in(0);
            if (expected[d] > 0)
              hints.push_back(own - stride);
            if (expected[d] + 2 < grid.n_nodes_in(d))
              hints.push_back(own + stride);
          }
        }
        for (const unsigned int hint : hints)
        {
          found = {{777, 777}};
          ASSERT_EQ(grid.locate(p, hint, found), inside) << p << " from cell " << hint;
          if (inside)
          {
            ASSERT_EQ(found, expected) << p << " from cell " << hint;
            hits += hint == grid.cell_index(expected);
          }
        }
      }
    EXPECT_GT(hits, 1000u);
  }
}
