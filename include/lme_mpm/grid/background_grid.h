#ifndef LME_MPM_GRID_BACKGROUND_GRID_H
#define LME_MPM_GRID_BACKGROUND_GRID_H

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/grid/tria.h>

#include <lme_mpm/base/dealii.h>

#include <algorithm>
#include <array>
#include <memory>
#include <vector>

namespace lme_mpm
{
/**
 * The fixed Cartesian background grid. deal.II owns the mesh (a
 * subdivided_hyper_rectangle, uniform or graded, with coloured boundary ids) and the
 * nodal DoF numbering used for grid output; the solver's hot loops use the
 * lexicographic node index i + n_0 (j + n_1 k), so locating a particle is index
 * arithmetic (uniform directions) or a binary search (graded ones), never a search
 * through cells.
 */
template <int dim>
class BackgroundGrid
{
public:
  static void declare_parameters(ParameterHandler &prm);
  /// Builds the grid from the "Grid" subsection.
  void parse_parameters(ParameterHandler &prm);
  /// Builds a grid from explicit step sizes per direction (graded if they differ).
  void reinit(const Point<dim> &lower, const std::array<std::vector<double>, dim> &steps);

  unsigned int n_nodes() const { return n_nodes_total; }
  unsigned int n_cells() const { return n_cells_total; }
  unsigned int n_cells_in(const unsigned int d) const { return coords[d].size() - 1; }
  unsigned int n_nodes_in(const unsigned int d) const { return coords[d].size(); }
  /// Stride of direction d in the node index.
  unsigned int node_stride(const unsigned int d) const { return node_strides[d]; }
  unsigned int cells_per_layer() const { return cell_strides[dim - 1]; }

  /// Node coordinates along direction d.
  const std::vector<double> &coordinates(const unsigned int d) const { return coords[d]; }
  double spacing(const unsigned int d, const unsigned int cell_i) const
  {
    return coords[d][cell_i + 1] - coords[d][cell_i];
  }
  /// Spacing at node @p node_i along d: the mean of the cells on either side of it
  /// (the one cell at an end). Node-based lengths stay continuous where cells change
  /// size, unlike the size of the cell a point happens to lie in.
  double nodal_spacing(const unsigned int d, const unsigned int node_i) const
  {
    const auto &c = coords[d];
    if (node_i == 0)
      return c[1] - c[0];
    if (node_i + 1 == c.size())
      return c[node_i] - c[node_i - 1];
    return 0.5 * (c[node_i + 1] - c[node_i - 1]);
  }
  double min_spacing() const { return h_min; }
  /// The largest cell size in any direction.
  double max_spacing() const { return h_max; }
  bool is_uniform(const unsigned int d) const { return uniform_h[d] > 0; }

  Point<dim> lower_corner() const;
  Point<dim> upper_corner() const;

  Point<dim> node_point(unsigned int node) const;
  unsigned int node_index(const std::array<unsigned int, dim> &ijk) const
  {
    unsigned int n = 0;
    for (unsigned int d = 0; d < dim; ++d)
      n += ijk[d] * node_strides[d];
    return n;
  }
  unsigned int cell_index(const std::array<unsigned int, dim> &ijk) const
  {
    unsigned int c = 0;
    for (unsigned int d = 0; d < dim; ++d)
      c += ijk[d] * cell_strides[d];
    return c;
  }
  /// Layer (index in the slowest direction) of a node.
  unsigned int node_layer(const unsigned int node) const
  {
    return node / node_strides[dim - 1];
  }
  unsigned int cell_layer(const unsigned int cell) const
  {
    return cell / cell_strides[dim - 1];
  }

  /**
   * Cartesian index of the cell holding x along direction d; false if x lies outside
   * the grid. A point on an interior cell face goes to the upper cell, one on the
   * upper grid face to the last cell.
   */
  bool locate(const double x, const unsigned int d, unsigned int &i) const
  {
    const auto &c = coords[d];
    if (!(x >= c.front() && x <= c.back()))
      return false;
    if (uniform_h[d] > 0)
    {
      // A multiply in place of the division: off by at most one at a face, which the
      // correction below settles against the coordinates themselves.
      const long k = static_cast<long>((x - c.front()) * inverse_uniform_h[d]);
      i            = static_cast<unsigned int>(std::min<long>(k, c.size() - 2));
      // Round-off at a cell face: correct by one.
      if (x < c[i] && i > 0)
        --i;
      else if (i + 2 < c.size() && x >= c[i + 1])
        ++i;
      return true;
    }
    return locate_graded(x, d, i);
  }
  bool locate(const Point<dim> &x, std::array<unsigned int, dim> &ijk) const
  {
    for (unsigned int d = 0; d < dim; ++d)
      if (!locate(x[d], d, ijk[d]))
        return false;
    return true;
  }
  /**
   * locate() for a point whose cell was found before (@p cell, a cell_index(), as
   * GridTransfer::locate_and_sort() keeps it per particle): the cell locate() gives
   * is the only one with c_i <= x < c_{i+1} along each direction (c_i <= x <= c_{i+1}
   * in the last cell), so where @p cell passes that test it is the answer, without
   * the search; where it does not (the point has moved, or @p cell is stale or out of
   * range), locate() finds it.
   */
  bool locate(const Point<dim> &x, const unsigned int cell,
              std::array<unsigned int, dim> &ijk) const
  {
    if (cell < n_cells_total)
    {
      unsigned int rest = cell;
      bool holds        = true;
      for (unsigned int d = dim; d-- > 0;)
      {
        const unsigned int i = d == 0 ? rest : rest / cell_strides[d];
        rest -= i * cell_strides[d];
        ijk[d]          = i;
        const double *c = coords[d].data() + i;
        holds &= (x[d] >= c[0]) &
                 ((x[d] < c[1]) | ((i + 2 == coords[d].size()) & (x[d] <= c[1])));
      }
      if (holds)
        return true;
    }
    return locate(x, ijk);
  }
  bool inside(const Point<dim> &x) const
  {
    for (unsigned int d = 0; d < dim; ++d)
      if (!(x[d] >= coords[d].front() && x[d] <= coords[d].back()))
        return false;
    return true;
  }

  /// Nodes on the grid faces with deal.II boundary id @p id (0: x-min, 1: x-max, ...).
  std::vector<unsigned int> nodes_on_boundary(types::boundary_id id) const;
  /// Nodes inside a closed box.
  std::vector<unsigned int> nodes_in_box(const BoundingBox<dim> &box) const;

  const Triangulation<dim> &triangulation() const { return tria; }
  const DoFHandler<dim> &dof_handler() const { return dofs; }
  /// DoF of component c of node n in dof_handler().
  types::global_dof_index dof(const unsigned int node, const unsigned int c) const
  {
    return node_to_dof[node * dim + c];
  }

private:
  /// locate() along a graded direction; inline, as every particle calls it a few times
  /// per step.
  bool locate_graded(const double x, const unsigned int d, unsigned int &i) const
  {
    // x is inside the grid (locate() checked); the bucket's cell is at most a step or
    // two off (a bucket is no wider than a cell; rounding of the product), settled
    // against the coordinates: c[i] <= x < c[i + 1], or the last cell for x on the
    // upper face.
    const auto &c       = coords[d];
    const auto &buckets = bucket_cell[d];
    const auto b = static_cast<std::size_t>((x - c.front()) * inverse_bucket_width[d]);
    i            = buckets[std::min(b, buckets.size() - 1)];
    while (i > 0 && x < c[i])
      --i;
    while (i + 2 < c.size() && x >= c[i + 1])
      ++i;
    return true;
  }

  std::array<std::vector<double>, dim> coords;
  std::array<double, dim> uniform_h{};
  std::array<double, dim> inverse_uniform_h{}; ///< 1 / uniform_h (0 where graded)
  /// Graded directions: the cell holding the lower end of each bucket of width the
  /// direction's smallest spacing, so that locating a point takes a lookup and at most
  /// a step or two instead of a binary search.
  std::array<std::vector<unsigned int>, dim> bucket_cell;
  std::array<double, dim> inverse_bucket_width{};
  std::array<unsigned int, dim> node_strides{};
  std::array<unsigned int, dim> cell_strides{};
  unsigned int n_nodes_total = 0, n_cells_total = 0;
  double h_min = 0, h_max = 0;

  Triangulation<dim> tria;
  std::unique_ptr<FESystem<dim>> fe;
  DoFHandler<dim> dofs;
  std::vector<types::global_dof_index> node_to_dof;
};
} // namespace lme_mpm

#endif
