// The row bound of LME's connectivity on graded grids (lme_kernels.h): the most nodes
// whose supports can reach a point of one cell. The bound combines only the distinct
// per-direction lists of the grid's cells; it must equal the count from the definition,
// cell by cell over every node.
#include <gtest/gtest.h>

#include "../../source/shape_functions/lme_kernels.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <iostream>
#include <random>
#include <vector>

using lme_mpm::shape_functions::lme_kernels::nodes_within_reach_bound;

namespace
{
/// A graded axis: runs of equal cells of random widths, as a graded scene grid has.
std::vector<double> graded_axis(std::mt19937 &rng, const unsigned int runs)
{
  std::uniform_int_distribution<int> length(1, 6);
  std::uniform_real_distribution<double> width(0.5, 2.0);
  std::vector<double> x = {0.0};
  for (unsigned int r = 0; r < runs; ++r)
  {
    const double h = width(rng);
    for (int k = length(rng); k > 0; --k)
      x.push_back(x.back() + h);
  }
  return x;
}

/// Per node: the smaller of its two adjacent spacings (the grid's convention).
std::vector<double> node_spacing(const std::vector<double> &x)
{
  std::vector<double> h(x.size());
  for (std::size_t i = 0; i < x.size(); ++i)
    h[i] = std::min(i > 0 ? x[i] - x[i - 1] : 1e300,
                    i + 1 < x.size() ? x[i + 1] - x[i] : 1e300);
  return h;
}

/// The definition: over every cell, the nodes I with a point of the cell within
/// radius_over_h * h_I, h_I the smallest of the node's spacings.
template <int dim>
unsigned int brute_force(const std::array<std::vector<double>, dim> &x,
                         const std::array<std::vector<double>, dim> &h, const double s)
{
  const auto gap = [](const std::vector<double> &c, const std::size_t cell,
                      const std::size_t i) {
    return std::max({0.0, c[cell] - c[i], c[i] - c[cell + 1]});
  };
  unsigned int most                  = 0;
  std::array<std::size_t, 3> n_cells = {1, 1, 1}, n_nodes = {1, 1, 1};
  for (unsigned int d = 0; d < dim; ++d)
    n_cells[d] = x[d].size() - 1, n_nodes[d] = x[d].size();
  for (std::size_t cz = 0; cz < n_cells[2]; ++cz)
    for (std::size_t cy = 0; cy < n_cells[1]; ++cy)
      for (std::size_t cx = 0; cx < n_cells[0]; ++cx)
      {
        unsigned int n = 0;
        for (std::size_t k = 0; k < n_nodes[2]; ++k)
          for (std::size_t j = 0; j < n_nodes[1]; ++j)
            for (std::size_t i = 0; i < n_nodes[0]; ++i)
            {
              const std::array<std::size_t, 3> cell = {cx, cy, cz}, node = {i, j, k};
              double g2 = 0, hI = 1e300;
              for (unsigned int d = 0; d < dim; ++d)
              {
                const double g = gap(x[d], cell[d], node[d]);
                g2 += g * g;
                hI = std::min(hI, h[d][node[d]]);
              }
              n += g2 <= s * s * hI * hI;
            }
        most = std::max(most, n);
      }
  return most;
}
} // namespace

TEST(LmeReachBound, EqualsTheCountFromTheDefinitionOnGradedGrids)
{
  std::mt19937 rng(3);
  for (const double s : {0.9, 1.7, 2.6})
  {
    std::array<std::vector<double>, 2> x2 = {graded_axis(rng, 6), graded_axis(rng, 5)};
    std::array<std::vector<double>, 2> h2 = {node_spacing(x2[0]), node_spacing(x2[1])};
    EXPECT_EQ(nodes_within_reach_bound<2>(x2, h2, s), brute_force<2>(x2, h2, s)) << s;
    std::array<std::vector<double>, 3> x3 = {graded_axis(rng, 3), graded_axis(rng, 3),
                                             graded_axis(rng, 2)};
    std::array<std::vector<double>, 3> h3 = {node_spacing(x3[0]), node_spacing(x3[1]),
                                             node_spacing(x3[2])};
    EXPECT_EQ(nodes_within_reach_bound<3>(x3, h3, s), brute_force<3>(x3, h3, s)) << s;
  }
}

TEST(LmeReachBound, CostsTheGridsClassesOfCellsNotItsCells)
{
  // 100^3 cells graded in three runs per direction (fine middle, coarse ends): the
  // bound took 0.22 s when every cell's lists were combined (Release), and takes about
  // a millisecond over the distinct lists; a return to the cell-by-cell cost fails.
  std::array<std::vector<double>, 3> x, h;
  for (unsigned int d = 0; d < 3; ++d)
  {
    x[d] = {0.0};
    for (unsigned int c = 0; c < 100; ++c)
      x[d].push_back(x[d].back() + (c < 30 || c >= 70 ? 0.02 : 0.01));
    h[d] = node_spacing(x[d]);
  }
  const auto start     = std::chrono::steady_clock::now();
  const unsigned int n = nodes_within_reach_bound<3>(x, h, 2.6);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "100^3 graded grid: bound " << n << " in " << seconds << " s" << std::endl;
  EXPECT_GT(n, 0u);
  EXPECT_LT(seconds, 0.05);
}

namespace
{
/// Nodes of the uniform grid of spacings h within R of x (the definition).
template <int dim>
unsigned int nodes_within(const std::array<double, dim> &x, const double R,
                          const std::array<double, dim> &h)
{
  const int m        = static_cast<int>(std::ceil(R / std::min(h[0], h[dim - 1]))) + 2;
  unsigned int count = 0;
  std::array<int, 3> i{};
  for (i[2] = dim == 3 ? -m : 0; i[2] <= (dim == 3 ? m : 0); ++i[2])
    for (i[1] = -m; i[1] <= m; ++i[1])
      for (i[0] = -m; i[0] <= m; ++i[0])
      {
        double r2 = 0;
        for (unsigned int d = 0; d < dim; ++d)
          r2 += std::pow(x[d] - i[d] * h[d], 2);
        count += r2 <= R * R;
      }
  return count;
}
} // namespace

TEST(LmeRowBound, BallOnALatticeBoundsEveryPointAndIsTighterThanTheRowCount)
{
  using lme_mpm::shape_functions::lme_kernels::nodes_in_ball_bound;
  using lme_mpm::shape_functions::lme_kernels::nodes_in_ball_on_lattice;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0, 1);
  // LME radii over h for gamma 0.8 to 4 at tolerance 1e-6, and unequal spacings.
  for (const double R : {1.86, 2.77, 4.16})
    for (const double hy : {1.0, 0.7})
    {
      const std::array<double, 2> h2 = {1.0, hy};
      const std::array<double, 3> h3 = {1.0, hy, 1.3};
      const unsigned int b2          = nodes_in_ball_on_lattice<2>(R * hy, h2),
                         b3          = nodes_in_ball_on_lattice<3>(R * hy, h3);
      unsigned int most2 = 0, most3 = 0;
      for (unsigned int s = 0; s < 4000; ++s)
      {
        const std::array<double, 2> x2 = {unit(rng), hy * unit(rng)};
        const std::array<double, 3> x3 = {unit(rng), hy * unit(rng), 1.3 * unit(rng)};
        most2                          = std::max(most2, nodes_within<2>(x2, R * hy, h2));
        if (s < 1000)
          most3 = std::max(most3, nodes_within<3>(x3, R * hy, h3));
      }
      EXPECT_GE(b2, most2) << R << ' ' << hy;
      EXPECT_GE(b3, most3) << R << ' ' << hy;
      EXPECT_LE(b2, nodes_in_ball_bound<2>(R * hy, h2));
      EXPECT_LE(b3, nodes_in_ball_bound<3>(R * hy, h3));
      // Close to what points reach: within 10 % in 2D and 15 % in 3D here.
      EXPECT_LE(b2, 1.10 * most2 + 1) << R << ' ' << hy;
      EXPECT_LE(b3, 1.15 * most3 + 1) << R << ' ' << hy;
    }
  // The figures the comment of nodes_in_ball_on_lattice() gives (gamma 1.8).
  EXPECT_EQ(nodes_in_ball_on_lattice<2>(2.77, {1.0, 1.0}), 27u);
  EXPECT_EQ(nodes_in_ball_on_lattice<3>(2.77, {1.0, 1.0, 1.0}), 99u);
}
