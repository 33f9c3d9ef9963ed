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
  // Kept as factors in 3D only: a 2D row of four nodes is 112 bytes against 80 as
  // factors, too few saved for the products formed in every pass (the 2D throughput
  // block ran 4 % slower with factors, the 3D one 17 % faster: doc/performance.md).
  unsigned int factor_width() const override { return dim == 3 ? 2 : 0; }
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
      SeparableRow<dim, 2> r;
      AssertThrow(grid.locate(x, r.i0),
                  ExcShapeFunctionFailure("linear", particles.id[p], point_to_string(x),
                                          "the particle is outside the grid"));
      for (unsigned int d = 0; d < dim; ++d)
      {
        // One division per direction (xi by the inverse: last-bit changes only).
        const double inv_h = 1 / grid.spacing(d, r.i0[d]);
        const double xi    = (x[d] - grid.coordinates(d)[r.i0[d]]) * inv_h;
        r.w[d]             = {{1 - xi, xi}};
        r.dw[d]            = {{-inv_h, inv_h}};
        r.n[d]             = 2;
      }
      store_row(grid, conn, p, r);
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
