#ifndef LME_MPM_SHAPE_FUNCTIONS_LME_SUPPORT_H
#define LME_MPM_SHAPE_FUNCTIONS_LME_SUPPORT_H

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <lme_mpm/grid/background_grid.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "lme_kernels.h"

namespace lme_mpm
{
namespace shape_functions
{
/**
 * Which nodes' supports hold a point, for the local max-ent functions: the support
 * search, apart from the multiplier's solve (lme.cc). On a uniform grid every node
 * reaches R = radius_over_h h; on a graded one node I reaches R_I = radius_over_h h_I,
 * h_I the smallest of its spacings. It sizes the connectivity's rows
 * (max_nodes()) and fills, per point, the nodes with their scaled offsets and the fixed
 * parts of their exponents.
 */
template <int dim>
class LmeSupport
{
public:
  /// The offsets of one point's nodes and the fixed parts of their exponents, and the
  /// search's own scratch; one per thread, reused from point to point.
  struct Offsets
  {
    std::vector<Tensor<1, dim>> y; ///< scaled offsets y_I = (x - x_I) / h (3D)
    std::vector<double> y0, y1;    ///< the y_I's components apart (2D kernels)
    std::vector<double> a;         ///< fixed part -gamma w_I |y_I|^2 of their exponents
    std::vector<double> w; ///< w_I = beta_I h^2 / gamma = (h / h_I)^2 (graded grids)
    std::array<std::vector<double>, dim> y1d; ///< (x_d - c_d[i]) / h in the index box
    std::array<std::vector<double>, dim> w1d; ///< (h / nodal spacing)^2 there (graded)
  };

  LmeSupport(const BackgroundGrid<dim> &grid, const double radius_over_h,
             const double gamma)
      : grid(grid), gamma(gamma), radius_over_h(radius_over_h)
  {
    // h of a cell is its smallest spacing, so the largest h over the grid is the
    // smallest over directions of the largest spacing in that direction.
    std::array<double, dim> h_min_d, h_max_d;
    double h_local_max = std::numeric_limits<double>::max();
    for (unsigned int d = 0; d < dim; ++d)
    {
      const auto &c = grid.coordinates(d);
      h_min_d[d]    = std::numeric_limits<double>::max();
      h_max_d[d]    = 0;
      for (unsigned int i = 0; i + 1 < c.size(); ++i)
      {
        h_min_d[d] = std::min(h_min_d[d], c[i + 1] - c[i]);
        h_max_d[d] = std::max(h_max_d[d], c[i + 1] - c[i]);
      }
      h_local_max = std::min(h_local_max, h_max_d[d]);
    }
    R_max = radius_over_h * h_local_max;
    for (unsigned int d = 0; d < dim; ++d)
      graded = graded || !grid.is_uniform(d);
    if (graded)
      for (unsigned int d = 0; d < dim; ++d)
        for (unsigned int i = 0; i < grid.n_nodes_in(d); ++i)
          node_h[d].push_back(grid.nodal_spacing(d, i));
    for (unsigned int d = 0; d < dim; ++d)
      set_up_box_walks(d);
    if (graded)
      set_up_weight_tables();
    max_nodes_ = 1;
    max_box_1d = 0;
    for (unsigned int d = 0; d < dim; ++d)
    {
      // Nodes of direction d within [x - R, x + R].
      const unsigned int b = std::min<unsigned int>(
          static_cast<unsigned int>(std::floor(2 * R_max / h_min_d[d])) + 2,
          grid.n_nodes_in(d));
      max_nodes_ *= b;
      max_box_1d = std::max(max_box_1d, b);
    }
    // The index box is up to 4 (2D) or 8 (3D) times the ball; the connectivity is
    // sized by this bound, so take the tighter count of the ball where it is smaller.
    max_nodes_ =
        std::min(max_nodes_, lme_kernels::nodes_in_ball_bound<dim>(R_max, h_min_d));
    // On a uniform grid the count over the cell's boxes is close to the most a point
    // has: the rows are that much shorter (28 slots instead of 32 in 2D, 100 instead
    // of 136 in 3D at gamma 1.8), and so is the memory they take.
    if (!graded)
      max_nodes_ = std::min(max_nodes_,
                            lme_kernels::nodes_in_ball_on_lattice<dim>(R_max, h_min_d));
    if (graded)
    {
      std::array<std::vector<double>, dim> coords;
      for (unsigned int d = 0; d < dim; ++d)
        coords[d] = grid.coordinates(d);
      max_nodes_ = std::min(max_nodes_, lme_kernels::nodes_within_reach_bound<dim>(
                                            coords, node_h, radius_over_h));
    }
    // Rows in whole groups of four for the SIMD passes.
    max_nodes_ = (max_nodes_ + 3) / 4 * 4;
  }

  /// Rows of the connectivity: at least the most nodes one point can have, in whole
  /// groups of four for the SIMD passes (lme_simd.h).
  unsigned int max_nodes() const { return max_nodes_; }
  /// The widest support on this grid.
  double widest_radius() const { return R_max; }
  bool is_graded() const { return graded; }
  /// Whether index_box() looks its weights up (a graded grid of few distinct spacings)
  /// rather than dividing per point.
  bool tables_weights() const { return !weights[0].empty(); }
  /// The reach of the node with Cartesian index @p node.
  double node_radius(const std::array<unsigned int, dim> &node) const
  {
    if (!graded)
      return R_max;
    double h = node_h[0][node[0]];
    for (unsigned int d = 1; d < dim; ++d)
      h = std::min(h, node_h[d][node[d]]);
    return radius_over_h * h; // the node's support is the ball of radius R h_I
  }
  /// Offsets sized for this grid.
  Offsets make_offsets() const
  {
    Offsets o;
    o.y.resize(max_nodes_), o.a.resize(max_nodes_), o.w.resize(max_nodes_);
    o.y0.resize(max_nodes_), o.y1.resize(max_nodes_);
    for (unsigned int d = 0; d < dim; ++d)
      o.y1d[d].resize(max_box_1d), o.w1d[d].resize(max_box_1d);
    return o;
  }

  /// Set-up of a point x: h, the smallest spacing of its cell (the unit of the scaled
  /// coordinates), and the n nodes whose support holds x (returns n) into @p nodes,
  /// their y_I, a_I and w_I into @p scratch; @p located is the cell x was last found in
  /// (BackgroundGrid::locate() with a cell). On a uniform grid (Graded false) the
  /// supports all have radius R = radius_over_h h; on a graded one node I reaches
  /// R_I = radius_over_h h_I. Calls fail(what...) (which must throw) if x is outside
  /// the grid or not strictly inside the nodes' hull.
  template <bool Graded, class Fail>
  unsigned int set_up(const Point<dim> &x, const unsigned int located,
                      unsigned int *nodes, Offsets &scratch, double &h,
                      const Fail &fail) const
  {
    std::array<unsigned int, dim> first, count, cell;
    if (!grid.locate(x, located, cell))
      fail("the particle is outside the grid");
    h = std::numeric_limits<double>::max();
    for (unsigned int d = 0; d < dim; ++d)
      h = std::min(h, grid.spacing(d, cell[d]));
    index_box<Graded>(x, cell, h, first, count, scratch);
    // The extent of the kept offsets, for the hull test.
    Tensor<1, dim> y_min, y_max;
    for (unsigned int d = 0; d < dim; ++d)
      y_min[d] = std::numeric_limits<double>::infinity(), y_max[d] = -y_min[d];
    unsigned int n;
    if constexpr (dim == 2 && !Graded)
      n = collect_uniform_2d(first, count, nodes, scratch, y_min, y_max, fail);
    else
      n = collect_by_rows<Graded>(first, count, nodes, scratch, y_min, y_max, fail);

    // The multiplier is finite only if x is strictly inside the hull of its
    // nodes; on a grid that needs nodes on both sides in every direction.
    for (unsigned int d = 0; d < dim; ++d)
      if (!(y_min[d] < 0 && y_max[d] > 0))
      {
        fail("the particle is not strictly inside the convex hull of its ", n,
             " nodes within reach (R = ", radius_over_h * h,
             " for the cell's spacing; no node on one side along direction ", d,
             "): it lies on the grid boundary, or the support is too small for its ",
             "cell (lower 'LME gamma' = ", gamma, " or 'LME tolerance')");
      }
    return n;
  }

private:
  /**
   * set_up() on a uniform 2D grid: the nodes of the index box inside the support, row
   * by row, with their offsets and exponents in @p scratch, and the extent of the
   * offsets in @p y_min, @p y_max; returns their number.
   */
  template <class Fail>
  unsigned int collect_uniform_2d(const std::array<unsigned int, dim> &first,
                                  const std::array<unsigned int, dim> &count,
                                  unsigned int *nodes, Offsets &scratch,
                                  Tensor<1, dim> &y_min, Tensor<1, dim> &y_max,
                                  const Fail &fail) const
  {
    const double R2 = radius_over_h * radius_over_h;
    const auto &y1d = scratch.y1d;
    unsigned int n  = 0;
    {
      // The kept nodes of a row are contiguous (u falls monotonically along it and q
      // grows with |u|): each row's range grows or shrinks from the last one's by the
      // support test itself, so exactly the nodes with q <= R2 are kept. sides
      // collects the signs of the kept offsets for the hull test below.
      unsigned int sides = 0;
      double *y0 = scratch.y0.data(), *y1 = scratch.y1.data(), *a = scratch.a.data();
      const double *u = y1d[0].data();
      const int last  = static_cast<int>(count[0]) - 1;
      int lo_prev = 0, hi_prev = -1;
      for (unsigned int j = 0; j < count[1]; ++j)
      {
        const double v  = y1d[1][j];
        const double qj = v * v;
        if (qj > R2)
          continue;
        const auto inside = [&](const int i) { return u[i] * u[i] + qj <= R2; };
        // Start from the last row's range (the first row: the node nearest x).
        if (hi_prev < lo_prev)
          lo_prev = hi_prev = std::clamp(static_cast<int>(u[0] + 0.5), 0, last);
        int lo = lo_prev, hi = hi_prev;
        while (lo > 0 && inside(lo - 1))
          --lo;
        while (lo <= hi && !inside(lo))
          ++lo;
        while (hi < last && inside(hi + 1))
          ++hi;
        while (hi >= lo && !inside(hi))
          --hi;
        if (hi < lo)
          continue;
        lo_prev = lo, hi_prev = hi;
        if (n + (hi - lo + 1) > max_nodes_)
          fail("more nodes in the support than max_nodes__per_particle()");
        const unsigned int row = (first[1] + j) * grid.node_stride(1) + first[0];
        for (int i = lo; i <= hi; ++i, ++n)
          nodes[n] = row + i, y0[n] = u[i], y1[n] = v, a[n] = -gamma * (u[i] * u[i] + qj);
        sides |= (v < 0 ? 4u : 0u) | (v > 0 ? 8u : 0u) | (u[hi] < 0 ? 1u : 0u) |
                 (u[lo] > 0 ? 2u : 0u);
      }
      if (sides != 15u)
        for (unsigned int I = 0; I < n; ++I)
          y_min[0] = std::min(y_min[0], y0[I]), y_max[0] = std::max(y_max[0], y0[I]),
          y_min[1] = std::min(y_min[1], y1[I]), y_max[1] = std::max(y_max[1], y1[I]);
      else
        y_min[0] = y_min[1] = -1, y_max[0] = y_max[1] = 1;
    }
    return n;
  }

  /**
   * set_up() on a graded 2D grid and in 3D: the nodes of the index box inside their
   * supports, as collect_uniform_2d().
   */
  template <bool Graded, class Fail>
  unsigned int collect_by_rows(const std::array<unsigned int, dim> &first,
                               const std::array<unsigned int, dim> &count,
                               unsigned int *nodes, Offsets &scratch,
                               Tensor<1, dim> &y_min, Tensor<1, dim> &y_max,
                               const Fail &fail) const
  {
    // Candidates inside their supports, in increasing node index order. q is |y_I|^2
    // weighted by w_I = (h / h_I)^2, with h_I the smallest of the node's spacings.
    const double R2 = radius_over_h * radius_over_h;
    const auto &y1d = scratch.y1d;
    const auto &w1d = scratch.w1d;
    unsigned int n  = 0;
    Tensor<1, dim> yI;
    // The outputs through local pointers and the extent in locals: written through
    // the references, every kept node would reload them (they might alias).
    double *const y0 = scratch.y0.data(), *const y1 = scratch.y1.data(),
                  *const a = scratch.a.data(), *const wI = scratch.w.data();
    Tensor<1, dim> *const y = scratch.y.data();
    Tensor<1, dim> lowest = y_min, highest = y_max;
    const auto keep = [&](const unsigned int node, const Tensor<1, dim> &yn,
                          const double q, const double w)
    {
      // Cannot happen (max_nodes_ bounds the ball); guards the connectivity row.
      if (n == max_nodes_)
        fail("more nodes in the support than max_nodes__per_particle()");
      nodes[n] = node;
      // 2D keeps the offsets apart only (the Chebyshev correction copies them).
      if constexpr (dim == 2)
        y0[n] = yn[0], y1[n] = yn[1];
      else
        y[n] = yn;
      a[n]  = -gamma * q;
      wI[n] = w;
      for (unsigned int d = 0; d < dim; ++d)
        lowest[d] = std::min(lowest[d], yn[d]), highest[d] = std::max(highest[d], yn[d]);
      ++n;
    };
    // The index box's offsets and weights through local pointers too.
    std::array<const double *, dim> u, wd;
    for (unsigned int d = 0; d < dim; ++d)
      u[d] = y1d[d].data(), wd[d] = w1d[d].data();
    // Weight of a node from those of its rows: the largest, as h_I is the smallest.
    const auto weight = [&](const unsigned int d, const unsigned int k)
    {
      if constexpr (Graded)
        return wd[d][k];
      else
        return 1.0;
    };
    if constexpr (dim == 2)
    {
      for (unsigned int j = 0; j < count[1]; ++j)
      {
        const double qj = u[1][j] * u[1][j];
        if (qj * weight(1, j) > R2)
          continue;
        const unsigned int row = (first[1] + j) * grid.node_stride(1) + first[0];
        for (unsigned int i = 0; i < count[0]; ++i)
        {
          const double w = std::max(weight(0, i), weight(1, j));
          const double q = w * (u[0][i] * u[0][i] + qj);
          if (q <= R2)
          {
            yI[0] = u[0][i], yI[1] = u[1][j];
            keep(row + i, yI, q, w);
          }
        }
      }
    }
    else
    {
      for (unsigned int k = 0; k < count[2]; ++k)
      {
        const double qk = u[2][k] * u[2][k];
        if (qk * weight(2, k) > R2)
          continue;
        for (unsigned int j = 0; j < count[1]; ++j)
        {
          const double qj  = u[1][j] * u[1][j] + qk;
          const double wjk = std::max(weight(1, j), weight(2, k));
          if (qj * wjk > R2)
            continue;
          const unsigned int row = (first[2] + k) * grid.node_stride(2) +
                                   (first[1] + j) * grid.node_stride(1) + first[0];
          for (unsigned int i = 0; i < count[0]; ++i)
          {
            const double w = std::max(weight(0, i), wjk);
            const double q = w * (u[0][i] * u[0][i] + qj);
            if (q <= R2)
            {
              yI[0] = u[0][i], yI[1] = u[1][j], yI[2] = u[2][k];
              keep(row + i, yI, q, w);
            }
          }
        }
      }
    }
    y_min = lowest, y_max = highest;
    return n;
  }

  /**
   * The index box of the nodes within [x - R, x + R] in each direction (R the widest
   * support that can reach x), and their scaled offsets (and weights, on a graded
   * grid) in @p scratch: first[d] and count[d] along each direction d.
   */
  template <bool Graded>
  void index_box(const Point<dim> &x, const std::array<unsigned int, dim> &cell,
                 const double h, std::array<unsigned int, dim> &first,
                 std::array<unsigned int, dim> &count, Offsets &scratch) const
  {
    const double inv_h = 1 / h;
    // The widest support that can reach x: R_max bounds every R_I.
    const double R = Graded ? R_max : radius_over_h * h;
    auto &y1d      = scratch.y1d;
    auto &w1d      = scratch.w1d;
    // The class of h, the smallest of the cell's spacings, is the smallest of theirs:
    // its weights' row in the tables (graded grids that keep them).
    unsigned int h_class = 0;
    if constexpr (Graded)
      if (!cell_class[0].empty())
      {
        h_class = cell_class[0][cell[0]];
        for (unsigned int e = 1; e < dim; ++e)
          h_class = std::min(h_class, cell_class[e][cell[e]]);
      }
    // The nodes of [x - R, x + R] along each d, walked to from x's cell (a few nodes
    // each way, cheaper than a search of graded coordinates and exact at the ends on
    // any grid); on a graded grid then trimmed at both ends to nodes that reach x
    // along d (h_I may be below R / radius_over_h there).
    for (unsigned int d = 0; d < dim; ++d)
    {
      const auto &c   = grid.coordinates(d);
      const double lo = x[d] - R, hi = x[d] + R;
      // The first node at or above lo and the last at or below hi, walked to from the
      // cell's bounds on them (BoxWalk), a step or none away.
      const BoxWalk &walk = walks[d][cell[d]];
      unsigned int i_lo   = walk.lo;
      while (c[i_lo] < lo)
        ++i_lo;
      unsigned int i_hi = walk.hi;
      while (c[i_hi] > hi)
        --i_hi;
      if constexpr (Graded)
      {
        // Trimmed to the nodes that reach x along d, from both ends. The nodes beyond
        // the cell's reach bounds reach no point of the cell, so the trim passes them
        // in one jump and tests the same nodes after them.
        const double *const R_d = node_R[d].data();
        const auto reaches      = [&](const unsigned int i)
        { return std::abs(x[d] - c[i]) <= R_d[i]; };
        i_lo = std::max(i_lo, std::min(walk.reach_lo, i_hi));
        while (i_lo < i_hi && !reaches(i_lo))
          ++i_lo;
        i_hi = std::min(i_hi, std::max(walk.reach_hi, i_lo));
        while (i_hi > i_lo && !reaches(i_hi))
          --i_hi;
      }
      first[d] = i_lo;
      count[d] = i_hi + 1 - i_lo;
      Assert(count[d] <= max_box_1d, ExcInternalError());
      // Through local pointers: a store through the vectors might alias their sources.
      double *const yd = y1d[d].data(), *const wd = w1d[d].data();
      const double *const cd = c.data() + i_lo;
      const double xd        = x[d];
      for (unsigned int k = 0; k < count[d]; ++k)
        yd[k] = (xd - cd[k]) * inv_h;
      if constexpr (Graded)
      {
        if (!weights[d].empty())
        {
          const double *const table = weights[d].data() + h_class * c.size() + i_lo;
          std::copy(table, table + count[d], wd);
        }
        else
        {
          const double *const hd = node_h[d].data() + i_lo;
          for (unsigned int k = 0; k < count[d]; ++k)
          {
            const double r = h / hd[k];
            wd[k]          = r * r;
          }
        }
      }
    }
  }

  /**
   * Bounds of index_box()'s walks for the points of one cell along one direction:
   * lo <= the first node at or above x - R_max and hi >= the last at or below
   * x + R_max for every x in the cell (on a uniform grid index_box()'s R is R_max to
   * rounding); on a graded grid no node below reach_lo or above reach_hi reaches a
   * point of the cell (|x - c_i| > R_i). Each holds with a margin far above the
   * rounding of the tests they stand for.
   */
  struct BoxWalk
  {
    unsigned int lo, hi, reach_lo, reach_hi;
  };

  /// walks[d], and node_R[d] on a graded grid, of direction @p d.
  void set_up_box_walks(const unsigned int d)
  {
    const std::vector<double> &c = grid.coordinates(d);
    const unsigned int n_nodes   = c.size();
    // On a uniform grid no node is trimmed: each reaches the whole box.
    node_R[d].assign(n_nodes, std::numeric_limits<double>::infinity());
    if (graded)
      for (unsigned int i = 0; i < n_nodes; ++i)
        node_R[d][i] = radius_over_h * node_h[d][i]; // the product reaches() tests
    const double margin =
        1e-9 * (std::max(std::abs(c.front()), std::abs(c.back())) + R_max);
    // Each bound moves one way as the cell does: carried from cell to cell.
    walks[d].resize(n_nodes - 1);
    unsigned int lo = 0, reach_lo = 0;
    for (unsigned int k = 0; k + 1 < n_nodes; ++k)
    {
      const double below = c[k] - margin;
      while (c[lo] < below - R_max)
        ++lo;
      while (c[reach_lo] + node_R[d][reach_lo] < below)
        ++reach_lo;
      walks[d][k].lo = lo, walks[d][k].reach_lo = reach_lo;
    }
    unsigned int hi = n_nodes - 1, reach_hi = n_nodes - 1;
    for (unsigned int k = n_nodes - 1; k-- > 0;)
    {
      const double above = c[k + 1] + margin;
      while (c[hi] > above + R_max)
        --hi;
      while (c[reach_hi] - node_R[d][reach_hi] > above)
        --reach_hi;
      walks[d][k].hi = hi, walks[d][k].reach_hi = reach_hi;
    }
  }

  /**
   * The weights (h / h_I)^2 of index_box() per class of cells with equal h, where the
   * grid has few distinct spacings (a graded grid of a few levels): looked up where
   * each point would divide. The same division, made once, so the same bits.
   */
  void set_up_weight_tables()
  {
    std::vector<double> spacings;
    for (unsigned int d = 0; d < dim; ++d)
      for (unsigned int k = 0; k < grid.n_cells_in(d); ++k)
        spacings.push_back(grid.spacing(d, k));
    std::sort(spacings.begin(), spacings.end());
    spacings.erase(std::unique(spacings.begin(), spacings.end()), spacings.end());
    std::size_t entries = 0;
    for (unsigned int d = 0; d < dim; ++d)
      entries += spacings.size() * grid.n_nodes_in(d);
    // A geometrically graded grid has a spacing per cell: divide as before there.
    if (entries > (std::size_t(1) << 18))
      return;
    for (unsigned int d = 0; d < dim; ++d)
    {
      for (unsigned int k = 0; k < grid.n_cells_in(d); ++k)
        cell_class[d].push_back(
            std::lower_bound(spacings.begin(), spacings.end(), grid.spacing(d, k)) -
            spacings.begin());
      const unsigned int n_nodes = grid.n_nodes_in(d);
      weights[d].resize(spacings.size() * n_nodes);
      for (std::size_t h_class = 0; h_class < spacings.size(); ++h_class)
        for (unsigned int i = 0; i < n_nodes; ++i)
        {
          const double r                    = spacings[h_class] / node_h[d][i];
          weights[d][h_class * n_nodes + i] = r * r;
        }
    }
  }

  const BackgroundGrid<dim> &grid;
  const double gamma;
  const double radius_over_h; ///< support radius R / h
  double R_max = 0;           ///< largest support radius on this grid
  bool graded  = false;       ///< nodal beta_I (any direction not uniform)
  std::array<std::vector<double>, dim> node_h; ///< nodal spacings (graded grids)
  /// Their reaches R_I (graded grids; infinite on uniform ones, where none is trimmed).
  std::array<std::vector<double>, dim> node_R;
  std::array<std::vector<BoxWalk>, dim> walks; ///< per cell along d
  /// Class (index into the sorted distinct spacings) of each cell's spacing along d,
  /// and per class and node along d the weight (h / h_I)^2; empty if too many.
  std::array<std::vector<unsigned int>, dim> cell_class;
  std::array<std::vector<double>, dim> weights;
  unsigned int max_nodes_;
  unsigned int max_box_1d;
};
} // namespace shape_functions
} // namespace lme_mpm

#endif
