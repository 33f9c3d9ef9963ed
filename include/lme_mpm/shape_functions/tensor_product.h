#ifndef LME_MPM_SHAPE_FUNCTIONS_TENSOR_PRODUCT_H
#define LME_MPM_SHAPE_FUNCTIONS_TENSOR_PRODUCT_H

#include <lme_mpm/shape_functions/shape_function.h>

#include <array>
#include <type_traits>

// The row walks are the inner loops of every transfer: inlined into them whatever the
// nesting of the lambdas around (the compiler's own limits left the grid-to-particle
// pass calling one per particle, twice as slow).
#if defined(__GNUC__)
#define LME_MPM_INLINE_ROW inline __attribute__((always_inline))
#define LME_MPM_INLINE_LAMBDA __attribute__((always_inline))
#else
#define LME_MPM_INLINE_ROW inline
#define LME_MPM_INLINE_LAMBDA
#endif

namespace lme_mpm
{
/**
 * Calls f(node, value, gradient) for every node of the tensor-product row @p r, in
 * increasing index order (the fastest direction first). The one place where a
 * separable row's products are formed: a row stored in full and one kept as its
 * factors give the same values to the bit.
 */
template <int dim, int max_1d, class F>
LME_MPM_INLINE_ROW void for_each_node(const BackgroundGrid<dim> &grid,
                                      const SeparableRow<dim, max_1d> &r, F &&f)
{
  // Node indices are linear in the Cartesian ones: the first node's, plus strides.
  const unsigned int first = grid.node_index(r.i0);
  std::array<unsigned int, dim> stride;
  for (unsigned int d = 0; d < dim; ++d)
  {
    std::array<unsigned int, dim> unit{};
    unit[d]   = 1;
    stride[d] = grid.node_index(unit);
  }
  const auto all_of_length = [&](const unsigned int k)
  {
    bool all = true;
    for (unsigned int d = 0; d < dim; ++d)
      all = all && r.n[d] == k;
    return all;
  };
  if constexpr (dim == 2)
  {
    const auto node = [&](const unsigned int a, const unsigned int b)
                          LME_MPM_INLINE_LAMBDA
    {
      Tensor<1, dim> g;
      g[0] = r.dw[0][a] * r.w[1][b];
      g[1] = r.w[0][a] * r.dw[1][b];
      f(first + a * stride[0] + b * stride[1], r.w[0][a] * r.w[1][b], g);
    };
    // Rows of a fixed length in every direction (B-splines away from the grid's
    // edges, uGIMP on uniform grids): loops of fixed length, unrolled.
    const auto fixed = [&](auto k) LME_MPM_INLINE_LAMBDA
    {
      for (unsigned int b = 0; b < decltype(k)::value; ++b)
        for (unsigned int a = 0; a < decltype(k)::value; ++a)
          node(a, b);
    };
    if (all_of_length(max_1d))
      fixed(std::integral_constant<unsigned int, max_1d>());
    else if (max_1d == 4 && all_of_length(3))
      fixed(std::integral_constant<unsigned int, 3>());
    else
      for (unsigned int b = 0; b < r.n[1]; ++b)
        for (unsigned int a = 0; a < r.n[0]; ++a)
          node(a, b);
  }
  else
  {
    const auto node = [&](const unsigned int a, const unsigned int b,
                          const unsigned int c) LME_MPM_INLINE_LAMBDA
    {
      Tensor<1, dim> g;
      g[0] = r.dw[0][a] * r.w[1][b] * r.w[2][c];
      g[1] = r.w[0][a] * r.dw[1][b] * r.w[2][c];
      g[2] = r.w[0][a] * r.w[1][b] * r.dw[2][c];
      f(first + a * stride[0] + b * stride[1] + c * stride[2],
        r.w[0][a] * r.w[1][b] * r.w[2][c], g);
    };
    const auto fixed = [&](auto k) LME_MPM_INLINE_LAMBDA
    {
      for (unsigned int c = 0; c < decltype(k)::value; ++c)
        for (unsigned int b = 0; b < decltype(k)::value; ++b)
          for (unsigned int a = 0; a < decltype(k)::value; ++a)
            node(a, b, c);
    };
    if (all_of_length(max_1d))
      fixed(std::integral_constant<unsigned int, max_1d>());
    else if (max_1d == 4 && all_of_length(3))
      fixed(std::integral_constant<unsigned int, 3>());
    else
      for (unsigned int c = 0; c < r.n[2]; ++c)
        for (unsigned int b = 0; b < r.n[1]; ++b)
          for (unsigned int a = 0; a < r.n[0]; ++a)
            node(a, b, c);
  }
}

/**
 * The Q1 hat functions of cell @p cell at point @p x, as 1D factors per direction.
 * The one place they are formed, so that a row stored and one formed again from the
 * cell by a walk (CellRows) agree to the bit.
 */
template <int dim>
LME_MPM_INLINE_ROW void
hat_row(const BackgroundGrid<dim> &grid, const Point<dim> &x,
        const std::common_type_t<std::array<unsigned int, dim>> &cell,
        SeparableRow<dim, 2> &r)
{
  r.i0 = cell;
  for (unsigned int d = 0; d < dim; ++d)
  {
    // One division per direction (xi by the inverse: last-bit changes only).
    const double inv_h = 1 / grid.spacing(d, cell[d]);
    const double xi    = (x[d] - grid.coordinates(d)[cell[d]]) * inv_h;
    r.w[d]             = {{1 - xi, xi}};
    r.dw[d]            = {{-inv_h, inv_h}};
    r.n[d]             = 2;
  }
}

/**
 * Builds a particle's row of the connectivity from 1D weights per direction: node
 * index i0[d] + k along d carries value w[d][k] and derivative dw[d][k], k < n[d].
 * Shared by the separable families (linear, uGIMP, B-spline). Nodes come out in
 * increasing index order (the fastest direction first).
 */
template <int dim, int max_1d>
inline unsigned int
tensor_product_row(const BackgroundGrid<dim> &grid, const SeparableRow<dim, max_1d> &r,
                   unsigned int *nodes, double *N, Tensor<1, dim> *grad_N)
{
  unsigned int count = 0;
  for_each_node(grid, r,
                [&](const unsigned int I, const double value, const Tensor<1, dim> &g)
                {
                  nodes[count]  = I;
                  N[count]      = value;
                  grad_N[count] = g;
                  ++count;
                });
  return count;
}

/// Particle @p p's row @p r into @p conn: as its factors where the connectivity keeps
/// rows of this width so, in full otherwise.
template <int dim, int max_1d>
LME_MPM_INLINE_ROW void store_row(const BackgroundGrid<dim> &grid,
                                  Connectivity<dim> &conn, const std::size_t p,
                                  const SeparableRow<dim, max_1d> &r)
{
  static_assert(max_1d == 2 || max_1d == 4, "rows of 2 or 4 nodes per direction");
  Assert(conn.factor_width == 0 || conn.factor_width == max_1d,
         ExcMessage("rows kept as factors of another width than the family's"));
  if (conn.factor_width == max_1d)
  {
    if constexpr (max_1d == 2)
      conn.factors_2[p] = r;
    else
      conn.factors_4[p] = r;
  }
  else
  {
#ifdef DEBUG
    unsigned int n_row = 1;
    for (unsigned int d = 0; d < dim; ++d)
      n_row *= r.n[d];
    Assert(conn.stride >= n_row, ExcInternalError());
#endif
    conn.n_nodes[p] =
        tensor_product_row(grid, r, &conn.nodes[p * conn.stride],
                           &conn.N[p * conn.stride], &conn.grad_N[p * conn.stride]);
  }
}

/**
 * The rows of a connectivity as the transfers read them: visit(p, f) calls
 * f(node, value, gradient) for each node of particle p's row in increasing index
 * order; first_and_last(p) gives its lowest and highest node. One type per way of
 * keeping the rows, so that the transfer loops are compiled for each.
 */
template <int dim>
struct FullRows
{
  const Connectivity<dim> &conn;
  template <class F>
  LME_MPM_INLINE_ROW void visit(const std::size_t p, F &&f) const
  {
    const std::size_t o = p * conn.stride;
    for (unsigned int k = 0; k < conn.n_nodes[p]; ++k)
      f(conn.nodes[o + k], conn.N[o + k], conn.grad_N[o + k]);
  }
  std::pair<unsigned int, unsigned int> first_and_last(const std::size_t p) const
  {
    const unsigned int *row = &conn.nodes[p * conn.stride];
    return {row[0], row[conn.n_nodes[p] - 1]};
  }
};

template <int dim, int max_1d>
struct FactorRows
{
  const BackgroundGrid<dim> &grid;
  const std::vector<SeparableRow<dim, max_1d>> &rows;
  template <class F>
  LME_MPM_INLINE_ROW void visit(const std::size_t p, F &&f) const
  {
    for_each_node(grid, rows[p], f);
  }
  std::pair<unsigned int, unsigned int> first_and_last(const std::size_t p) const
  {
    const SeparableRow<dim, max_1d> &r = rows[p];
    std::array<unsigned int, dim> last;
    for (unsigned int d = 0; d < dim; ++d)
      last[d] = r.i0[d] + r.n[d] - 1;
    return {grid.node_index(r.i0), grid.node_index(last)};
  }
};

/// Q1 hat rows formed from each particle's cell and position as they are walked.
template <int dim>
struct CellRows
{
  const BackgroundGrid<dim> &grid;
  const std::vector<std::array<unsigned int, dim>> &cells;
  const std::vector<Point<dim>> &positions;
  template <class F>
  LME_MPM_INLINE_ROW void visit(const std::size_t p, F &&f) const
  {
    SeparableRow<dim, 2> r;
    hat_row(grid, positions[p], cells[p], r);
    for_each_node(grid, r, f);
  }
  std::pair<unsigned int, unsigned int> first_and_last(const std::size_t p) const
  {
    std::array<unsigned int, dim> last = cells[p];
    for (unsigned int d = 0; d < dim; ++d)
      ++last[d];
    return {grid.node_index(cells[p]), grid.node_index(last)};
  }
};

/// Calls f(rows) with the rows of @p conn as one of the types above.
template <int dim, class F>
inline void with_rows(const BackgroundGrid<dim> &grid, const Connectivity<dim> &conn,
                      F &&f)
{
  if (conn.hat_rows_from_cells)
    f(CellRows<dim>{grid, conn.cells, *conn.positions});
  else if (conn.factor_width == 2)
    f(FactorRows<dim, 2>{grid, conn.factors_2});
  else if (conn.factor_width == 4)
    f(FactorRows<dim, 4>{grid, conn.factors_4});
  else
    f(FullRows<dim>{conn});
}
} // namespace lme_mpm

#endif
