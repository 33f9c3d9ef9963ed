#include <lme_mpm/base/format.h>
#include <lme_mpm/shape_functions/tensor_product.h>

namespace lme_mpm
{
namespace shape_functions
{
/**
 * Standard MPM: the tensor-product Q1 hat functions of the background cell that
 * holds the particle (2^dim nodes). Exact for linear fields, but gradients jump
 * when a particle crosses a cell face (the cell-crossing error).
 */
template <int dim>
class Linear : public ShapeFunction<dim>
{
public:
  static void declare_parameters(ParameterHandler &) {}

  Linear(ParameterHandler &, const ShapeFunctionContext<dim> &context)
      : grid(*context.grid)
  {
  }

  std::string name() const override { return "linear"; }
  unsigned int max_nodes_per_particle() const override { return 1u << dim; }
  unsigned int factor_width() const override { return 2; }
  // Where only the transfers read the rows, the connectivity keeps the cell alone
  // (8 or 12 bytes against a full 2D row of 112, or 120 as 3D factors):
  // doc/performance.md.
  bool rows_are_cell_hats() const override { return true; }
  double support_radius(const BackgroundGrid<dim> &g) const override
  {
    return this->largest_cell_diagonal(g); // the far corner of the particle's cell
  }
  double node_support_radius(const BackgroundGrid<dim> &g,
                             const std::array<unsigned int, dim> &node) const override
  {
    return 1.0 * this->cell_diagonal_near(g, node, 1);
  }

  void compute(ParticleStore<dim> &particles, const std::size_t begin,
               const std::size_t end, Connectivity<dim> &conn) const override
  {
    for (std::size_t p = begin; p < end; ++p)
    {
      const Point<dim> &x = particles.position[p];
      std::array<unsigned int, dim> cell;
      AssertThrow(grid.locate(x, particles.cell[p], cell),
                  ExcShapeFunctionFailure("linear", particles.id[p], point_to_string(x),
                                          "the particle is outside the grid"));
      if (conn.hat_rows_from_cells)
        conn.cells[p] = cell;
      else
      {
        SeparableRow<dim, 2> r;
        hat_row(grid, x, cell, r);
        store_row(grid, conn, p, r);
      }
    }
  }

private:
  const BackgroundGrid<dim> &grid;
};
} // namespace shape_functions
} // namespace lme_mpm

using lme_mpm::shape_functions::Linear;
LME_MPM_REGISTER_SHAPE_FUNCTION(Linear, "linear",
                                "tensor-product Q1 hat functions of the cell that holds "
                                "the particle (standard MPM).")
