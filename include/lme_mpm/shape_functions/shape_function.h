#ifndef LME_MPM_SHAPE_FUNCTIONS_SHAPE_FUNCTION_H
#define LME_MPM_SHAPE_FUNCTIONS_SHAPE_FUNCTION_H

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <lme_mpm/base/registry.h>
#include <lme_mpm/grid/background_grid.h>
#include <lme_mpm/particles/particle_store.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace lme_mpm
{
/**
 * A tensor-product row kept as its factors: along each direction d the nodes
 * i0[d] + k, k < n[d], with 1D values w[d][k] and derivatives dw[d][k]. The row's
 * values and gradients are their products (tensor_product.h), formed where they are
 * used: a few bytes per direction in place of a value and a gradient per node.
 */
template <int dim, int max_1d>
struct SeparableRow
{
  std::array<unsigned int, dim> i0, n;
  std::array<std::array<double, max_1d>, dim> w, dw;
};

/**
 * Particle-node coupling for one step, stored flat: particle p owns the slots
 * [p * stride, p * stride + n_nodes[p]) of `nodes`, `N` and `grad_N`, with its nodes
 * in increasing index order. Computed once per step and shared by every transfer.
 *
 * Where only the transfers read the rows (no explicit cracks, body fields, rigid
 * surfaces or mass matrix) and the functions are a tensor product of at most
 * `factor_width` nodes per direction, each row is kept as its factors instead
 * (`factors_2` or `factors_4`); `n_nodes`, `nodes`, `N` and `grad_N` are then empty.
 * Rows of the linear family (Q1 hats of the particle's cell) are then kept as the cell
 * alone (`cells`) and formed again from the position by each walk.
 */
template <int dim>
struct Connectivity
{
  unsigned int stride = 0;
  /// 0: full rows; 2 or 4: rows kept as factors in factors_2 or factors_4.
  unsigned int factor_width = 0;
  /// Q1 hat rows kept as the particle's cell alone (`cells`), formed from the cell and
  /// the particle's position (`positions`) by every walk: see hat_row().
  bool hat_rows_from_cells = false;
  std::vector<unsigned int> n_nodes;
  std::vector<unsigned int> nodes;
  std::vector<double> N;
  std::vector<Tensor<1, dim>> grad_N;
  std::vector<SeparableRow<dim, 2>> factors_2;
  std::vector<SeparableRow<dim, 4>> factors_4;
  std::vector<std::array<unsigned int, dim>> cells;
  const std::vector<Point<dim>> *positions = nullptr;
  void resize(const std::size_t n_particles, const unsigned int max_nodes)
  {
    stride              = max_nodes;
    factor_width        = 0;
    hat_rows_from_cells = false;
    n_nodes.resize(n_particles);
    nodes.resize(n_particles * stride);
    N.resize(n_particles * stride);
    grad_N.resize(n_particles * stride);
  }
  /// Rows kept as factors of at most @p width (2 or 4) nodes per direction; the full
  /// rows' memory, n_nodes included, is released (their walks count the nodes).
  void resize_factors(const std::size_t n_particles, const unsigned int width)
  {
    stride              = 0;
    factor_width        = width;
    hat_rows_from_cells = false;
    release_full_rows();
    if (width == 2)
      factors_2.resize(n_particles);
    else
      factors_4.resize(n_particles);
  }
  /// Q1 hat rows kept as each particle's cell; @p x are the particles' positions, which
  /// must not change while the rows are read.
  void resize_cells(const std::size_t n_particles, const std::vector<Point<dim>> &x)
  {
    stride              = 0;
    factor_width        = 2;
    hat_rows_from_cells = true;
    positions           = &x;
    release_full_rows();
    std::vector<SeparableRow<dim, 2>>().swap(factors_2);
    cells.resize(n_particles);
  }

private:
  void release_full_rows()
  {
    std::vector<unsigned int>().swap(n_nodes);
    std::vector<unsigned int>().swap(nodes);
    std::vector<double>().swap(N);
    std::vector<Tensor<1, dim>>().swap(grad_N);
  }
};

/// What a shape function may need to know about the problem when it is built.
template <int dim>
struct ShapeFunctionContext
{
  const BackgroundGrid<dim> *grid = nullptr;
  double thickness                = 1.0; ///< 2D out-of-plane thickness
};

/// A particle the shape functions cannot be evaluated at; the run stops.
DeclException4(ExcShapeFunctionFailure, std::string, unsigned int, std::string,
               std::string, << arg1 << " shape functions failed at particle " << arg2
                            << " (position " << arg3 << "): " << arg4);

/**
 * Interface of a family of shape functions (linear, uGIMP, cubic B-spline, LME).
 * compute() fills the connectivity of a range of particles in one call, so the hot
 * loop makes no virtual call per particle; it may read and update per-particle
 * state kept in the store (the LME multiplier).
 */
template <int dim>
class ShapeFunction
{
public:
  virtual ~ShapeFunction() = default;

  virtual std::string name() const = 0;

  /**
   * True if compute() reads and writes the shape functions' per-particle state
   * (ParticleStore::lme_lambda, lme_position, lme_lambda_rate: a warm start). A run
   * whose functions keep none drops those fields.
   */
  virtual bool keeps_particle_state() const { return false; }

  /// Upper bound of nodes coupled to one particle on this grid.
  virtual unsigned int max_nodes_per_particle() const = 0;
  /**
   * For a tensor-product family: the most nodes per direction of a row (2 or 4), if
   * compute() can keep its rows as their factors (Connectivity::factor_width set by
   * the caller; store_row() in tensor_product.h). 0 (the default): full rows only.
   */
  virtual unsigned int factor_width() const { return 0; }
  /**
   * True only if the rows are the tensor-product Q1 hat functions of the cell that
   * holds the particle, as hat_row() (tensor_product.h) forms them. Where only the
   * transfers read the rows, the connectivity then keeps each particle's cell alone
   * (Connectivity::hat_rows_from_cells) and every walk forms the row from the cell
   * and the position, which costs less than reading a stored row.
   */
  virtual bool rows_are_cell_hats() const { return false; }

  /**
   * Upper bound of the distance between a particle and a node of its support (m);
   * explicit cracks give a second field to the nodes this close to them. The default
   * bounds it by a box of max_nodes_per_particle() nodes of the widest cells.
   */
  virtual double support_radius(const BackgroundGrid<dim> &grid) const
  {
    const double width = std::ceil(std::pow(max_nodes_per_particle(), 1.0 / dim) - 1e-9);
    return width * largest_cell_diagonal(grid);
  }

  /**
   * Upper bound of the distance between grid node @p node (its index along each
   * direction) and a particle it couples to (m). Where the grid is graded this is
   * shorter than support_radius() in the fine cells, and a distributed run's halo
   * follows it; the default is support_radius() everywhere.
   */
  virtual double node_support_radius(const BackgroundGrid<dim> &grid,
                                     const std::array<unsigned int, dim> &node) const
  {
    (void)node;
    return support_radius(grid);
  }

  /**
   * Diagonal of a cell with the largest spacing of each direction among the cells
   * within @p k cells of @p node: how far supports @p k cells wide reach from it.
   */
  static double cell_diagonal_near(const BackgroundGrid<dim> &grid,
                                   const std::array<unsigned int, dim> &node,
                                   const unsigned int k)
  {
    double d2 = 0;
    for (unsigned int d = 0; d < dim; ++d)
    {
      const unsigned int n  = grid.n_cells_in(d);
      const unsigned int lo = node[d] > k ? node[d] - k : 0,
                         hi = std::min(n, node[d] + k);
      double h              = 0;
      for (unsigned int i = lo; i < hi; ++i)
        h = std::max(h, grid.spacing(d, i));
      d2 += h * h;
    }
    return std::sqrt(d2);
  }

  /// Diagonal of a cell with the largest spacing of each direction.
  static double largest_cell_diagonal(const BackgroundGrid<dim> &grid)
  {
    double d2 = 0;
    for (unsigned int d = 0; d < dim; ++d)
    {
      double h = 0;
      for (unsigned int i = 0; i + 1 < grid.coordinates(d).size(); ++i)
        h = std::max(h, grid.spacing(d, i));
      d2 += h * h;
    }
    return std::sqrt(d2);
  }

  /**
   * Fills rows [begin, end) of @p conn for the particles' current positions. Called
   * concurrently on disjoint ranges. Throws ExcShapeFunctionFailure on a particle
   * outside the region where the functions are defined or a failed solve. In a step,
   * `particles.cell` holds the cells GridTransfer::locate_and_sort() has just found:
   * BackgroundGrid::locate(x, particles.cell[p], ijk) takes it where it still holds x
   * and searches otherwise (as when compute() is called on a store never located).
   */
  virtual void compute(ParticleStore<dim> &particles, std::size_t begin, std::size_t end,
                       Connectivity<dim> &conn) const = 0;

  /// Counters reported in summary.json (for example Newton iterations).
  virtual std::vector<std::pair<std::string, double>> statistics() const { return {}; }
};

template <int dim>
using ShapeFunctionRegistry = Registry<ShapeFunction<dim>, ShapeFunctionContext<dim>>;

/// Declares "Shape functions/Type" and every registered family's entries beside it in
/// "Shape functions".
template <int dim>
void declare_shape_function_parameters(ParameterHandler &prm);
/// Builds the family "Shape functions/Type" names, on the grid of @p context.
template <int dim>
std::unique_ptr<ShapeFunction<dim>>
create_shape_function(ParameterHandler &prm, const ShapeFunctionContext<dim> &context);
} // namespace lme_mpm

/**
 * Registers shape-function class template CLASS (templated on dim, constructed from
 * (ParameterHandler &, const ShapeFunctionContext<dim> &), with a static
 * declare_parameters(ParameterHandler &)) under NAME for dim = 2 and 3. Its entries
 * are declared directly in the "Shape functions" subsection.
 */
#define LME_MPM_REGISTER_SHAPE_FUNCTION(CLASS, NAME, DESCRIPTION)                        \
  LME_MPM_REGISTER_PLUGIN_FOR_DIMS(::lme_mpm::ShapeFunctionRegistry, shape_function,     \
                                   CLASS, NAME, DESCRIPTION,                             \
                                   ::lme_mpm::PluginEntries::caller_subsection)

#endif
