// The halo of a distributed run, on one rank: the cells a set of cells reads through
// supports, fracture reach and margin, against a brute-force search, on uniform and
// graded grids.
#include <gtest/gtest.h>

#include <lme_mpm/distributed/halo.h>

#include <cmath>
#include <random>

using namespace lme_mpm;

namespace
{
/// Distance from node n to the box of cell c.
double node_gap(const BackgroundGrid<2> &grid, const unsigned int n, const unsigned int c)
{
  const Point<2> x      = grid.node_point(n);
  const unsigned int n0 = grid.n_cells_in(0);
  double d2             = 0;
  for (unsigned int d = 0; d < 2; ++d)
  {
    const unsigned int i = d == 0 ? c % n0 : c / n0;
    const auto &co       = grid.coordinates(d);
    const double gap     = std::max(0.0, std::max(co[i] - x[d], x[d] - co[i + 1]));
    d2 += gap * gap;
  }
  return std::sqrt(d2);
}

/// What HaloCells::reached computes, by testing every pair (balls, not boxes: it
/// must hold everything the brute force finds, and a box around each ball more).
std::vector<std::uint8_t> brute_force(const BackgroundGrid<2> &grid, const HaloReach &r,
                                      std::vector<std::uint8_t> mask)
{
  const unsigned int nc = grid.n_cells(), nn = grid.n_nodes();
  for (unsigned int pass = 0; pass < r.support_passes; ++pass)
  {
    std::vector<std::uint8_t> touched(nn, 0), next = mask;
    for (unsigned int n = 0; n < nn; ++n)
      for (unsigned int c = 0; c < nc && !touched[n]; ++c)
        touched[n] = mask[c] && node_gap(grid, n, c) <= r.node_radius[n];
    for (unsigned int n = 0; n < nn; ++n)
      if (touched[n])
        for (unsigned int c = 0; c < nc; ++c)
          next[c] |= node_gap(grid, n, c) <= r.node_radius[n];
    mask.swap(next);
  }
  return mask;
}
} // namespace

TEST(HaloCells, ReachedHoldsWhatTheSupportsReach)
{
  BackgroundGrid<2> grid;
  std::vector<double> x = {0.2, 0.2, 0.1, 0.05, 0.05, 0.05, 0.05, 0.1, 0.2, 0.2};
  grid.reinit(Point<2>(0, 0), {{x, std::vector<double>(8, 0.1)}});
  HaloReach reach;
  reach.support_passes = 2;
  reach.margin_cells   = 0;
  reach.node_radius.resize(grid.n_nodes());
  for (unsigned int n = 0; n < grid.n_nodes(); ++n)
    reach.node_radius[n] = 0.08 + 0.05 * (n % 3);
  const HaloCells<2> halo(grid, reach);
  std::mt19937 rng(5);
  for (int trial = 0; trial < 5; ++trial)
  {
    std::vector<std::uint8_t> mask(grid.n_cells(), 0);
    for (int k = 0; k < 3; ++k)
      mask[rng() % grid.n_cells()] = 1;
    const auto fast    = halo.reached(mask);
    const auto exact   = brute_force(grid, reach, mask);
    unsigned int extra = 0;
    for (unsigned int c = 0; c < grid.n_cells(); ++c)
    {
      EXPECT_TRUE(!exact[c] || fast[c]) << "cell " << c << " is read but not in the halo";
      extra += fast[c] && !exact[c];
    }
    // Boxes hold their balls with little to spare.
    EXPECT_LT(extra, grid.n_cells() / 2);
  }
}

TEST(HaloCells, FractureReachGoesBothWaysAndMarginIsCells)
{
  BackgroundGrid<2> grid;
  grid.reinit(Point<2>(0, 0),
              {{std::vector<double>(10, 0.1), std::vector<double>(10, 0.1)}});
  HaloReach reach;
  reach.node_radius.assign(grid.n_nodes(), 0.1);
  reach.cell_radius.assign(grid.n_cells(), 0.0);
  reach.cell_radius[55] = 0.25; // one cell with a long fracture reach
  reach.margin_cells    = 0;
  const HaloCells<2> halo(grid, reach);
  std::vector<std::uint8_t> mask(grid.n_cells(), 0);
  mask[52]       = 1; // three cells from 55 along x
  const auto out = halo.reached(mask);
  // A reach of 0 still touches the neighbouring cells (their faces meet); cell 55
  // reaches 52 (0.2 apart), so 52 reads it, but not 56 (0.3 apart).
  for (unsigned int c = 0; c < grid.n_cells(); ++c)
  {
    const int i = c % 10, j = c / 10;
    EXPECT_EQ(out[c], (std::abs(i - 2) <= 1 && std::abs(j - 5) <= 1) || c == 55) << c;
  }
  // Dilation by k cells along each direction: a square of side 2k + 1.
  const auto dilated = halo.dilate(mask, {{2, 1}});
  unsigned int count = 0;
  for (unsigned int c = 0; c < grid.n_cells(); ++c)
  {
    const int i = c % 10, j = c / 10;
    const bool inside = std::abs(i - 2) <= 2 && std::abs(j - 5) <= 1;
    EXPECT_EQ(dilated[c], inside) << c;
    count += dilated[c];
  }
  EXPECT_EQ(count, 15u);
  // A width of 0.25 over 0.1 cells from anywhere in a cell: 3 cells, one more.
  EXPECT_EQ(halo.cells_within(0.25)[0], 4u);
}
