#include <lme_mpm/distributed/halo.h>

#include "cell_boxes.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lme_mpm
{
template <int dim>
HaloCells<dim>::HaloCells(const BackgroundGrid<dim> &grid) : grid(grid)
{
}

template <int dim>
HaloCells<dim>::HaloCells(const BackgroundGrid<dim> &grid, const HaloReach &r)
    : grid(grid), reach(r)
{
  AssertThrow(
      reach.node_radius.size() == grid.n_nodes() &&
          (reach.cell_radius.empty() || reach.cell_radius.size() == grid.n_cells()),
      ExcInternalError());
  // A node's box: the cells within its radius (a box holds the ball).
  if (reach.support_passes > 0)
  {
    node_box.resize(grid.n_nodes());
    std::array<unsigned int, dim> ijk{};
    for (unsigned int a = 0; a < grid.n_nodes(); ++a)
    {
      for (unsigned int d = 0; d < dim; ++d)
      {
        const double x = grid.coordinates(d)[ijk[d]];
        cells_near(grid.coordinates(d), x, x, reach.node_radius[a], node_box[a].lo[d],
                   node_box[a].hi[d]);
      }
      for (unsigned int d = 0; d < dim && ++ijk[d] == grid.n_nodes_in(d); ++d)
        ijk[d] = 0;
    }
  }
  if (!reach.cell_radius.empty())
  {
    cell_box.resize(grid.n_cells());
    CellBoxes<dim>(cells_per_direction())
        .for_cells(
            [&](const std::size_t c, const std::array<unsigned int, dim> &ijk)
            {
              for (unsigned int d = 0; d < dim; ++d)
                cells_near(grid.coordinates(d), grid.coordinates(d)[ijk[d]],
                           grid.coordinates(d)[ijk[d] + 1], reach.cell_radius[c],
                           cell_box[c].lo[d], cell_box[c].hi[d]);
            });
  }
}

template <int dim>
std::array<unsigned int, dim> HaloCells<dim>::cells_per_direction() const
{
  std::array<unsigned int, dim> n;
  for (unsigned int d = 0; d < dim; ++d)
    n[d] = grid.n_cells_in(d);
  return n;
}

template <int dim>
std::vector<std::uint8_t>
HaloCells<dim>::reached(const std::vector<std::uint8_t> &mask) const
{
  CellBoxes<dim> boxes(cells_per_direction());
  std::vector<std::uint8_t> out = mask;
  for (unsigned int pass = 0; pass < reach.support_passes; ++pass)
  {
    // The nodes coupled to a flagged cell's particles, then their particles' cells.
    boxes.tabulate(out);
    std::vector<std::uint8_t> touched(node_box.size());
    for (std::size_t a = 0; a < node_box.size(); ++a)
      touched[a] = boxes.any(node_box[a]);
    boxes.clear();
    for (std::size_t a = 0; a < node_box.size(); ++a)
      if (touched[a])
        boxes.paint(node_box[a]);
    boxes.painted(out);
  }
  if (!cell_box.empty())
  {
    // A cell reaching a flagged one, and every cell a flagged one reaches.
    boxes.tabulate(out);
    std::vector<std::uint8_t> next = out;
    for (std::size_t c = 0; c < out.size(); ++c)
      next[c] |= boxes.any(cell_box[c]);
    boxes.clear();
    for (std::size_t c = 0; c < out.size(); ++c)
      if (out[c])
        boxes.paint(cell_box[c]);
    boxes.painted(next);
    out.swap(next);
  }
  if (reach.margin_cells > 0)
  {
    std::array<unsigned int, dim> k;
    k.fill(reach.margin_cells);
    out = dilate(out, k);
  }
  return out;
}

template <int dim>
std::array<unsigned int, dim> HaloCells<dim>::cells_within(const double width) const
{
  // The width over the narrowest cells of each direction, and one cell more (a
  // particle sits anywhere in its cell).
  std::array<unsigned int, dim> k;
  for (unsigned int d = 0; d < dim; ++d)
  {
    double h = std::numeric_limits<double>::max();
    for (unsigned int i = 0; i < grid.n_cells_in(d); ++i)
      h = std::min(h, grid.spacing(d, i));
    k[d] = static_cast<unsigned int>(
        std::min<double>(grid.n_cells_in(d), std::ceil(width / h - 1e-9) + 1));
  }
  return k;
}

template <int dim>
std::vector<std::uint8_t>
HaloCells<dim>::dilate(const std::vector<std::uint8_t> &mask,
                       const std::array<unsigned int, dim> &k) const
{
  const std::array<unsigned int, dim> n = cells_per_direction();
  CellBoxes<dim> boxes(n);
  boxes.for_cells(
      [&](const std::size_t c, const std::array<unsigned int, dim> &ijk)
      {
        if (!mask[c])
          return;
        CellBox<dim> b;
        for (unsigned int d = 0; d < dim; ++d)
          b.lo[d] = ijk[d] > k[d] ? ijk[d] - k[d] : 0,
          b.hi[d] = std::min(n[d], ijk[d] + k[d] + 1);
        boxes.paint(b);
      });
  std::vector<std::uint8_t> out = mask;
  boxes.painted(out);
  return out;
}

template class HaloCells<2>;
template class HaloCells<3>;
} // namespace lme_mpm
