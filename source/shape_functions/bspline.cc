#include <lme_mpm/base/format.h>
#include <lme_mpm/shape_functions/tensor_product.h>

#include <cmath>

namespace lme_mpm
{
namespace shape_functions
{
/**
 * Cubic B-splines centred on the grid nodes (support 2h, 4 nodes per direction):
 * C2 weights, so particles crossing cell faces see smooth gradients, and
 * non-negative. The spline basis needs a node beyond each grid edge; instead of
 * adding ghost nodes, the missing node's value is taken as the linear
 * extrapolation v_{-1} = 2 v_0 - v_1, which folds its weight into the two edge
 * nodes and keeps partition of unity and linear reproduction up to the boundary.
 * Defined for uniform spacing only (each direction may have its own h).
 */
template <int dim>
class BSpline : public ShapeFunction<dim>
{
public:
  static void declare_parameters(ParameterHandler &) {}

  BSpline(ParameterHandler &, const ShapeFunctionContext<dim> &context)
      : grid(*context.grid)
  {
    static const char *axis[3] = {"x", "y", "z"};
    for (unsigned int d = 0; d < dim; ++d)
    {
      AssertThrow(grid.is_uniform(d),
                  ExcMessage(std::string("Shape functions/Type = bspline needs a "
                                         "uniform grid, but the spacing along ") +
                             axis[d] +
                             " is graded; choose 'ugimp', 'lme' or 'linear' for a "
                             "graded grid."));
      h[d] = grid.spacing(d, 0);
    }
  }

  std::string name() const override { return "bspline"; }
  unsigned int max_nodes_per_particle() const override { return 1u << (2 * dim); }
  unsigned int factor_width() const override { return 4; }
  double support_radius(const BackgroundGrid<dim> &g) const override
  {
    return 2 * this->largest_cell_diagonal(g); // support 2 h per direction
  }

  void compute(ParticleStore<dim> &particles, const std::size_t begin,
               const std::size_t end, Connectivity<dim> &conn) const override
  {
    Assert(conn.factor_width == 4 || conn.stride >= max_nodes_per_particle(),
           ExcInternalError());
    for (std::size_t p = begin; p < end; ++p)
    {
      const Point<dim> &x = particles.position[p];
      std::array<unsigned int, dim> cell;
      SeparableRow<dim, 4> r;
      auto &w = r.w, &dw = r.dw;
      AssertThrow(grid.locate(x, particles.cell[p], cell),
                  ExcShapeFunctionFailure("bspline", particles.id[p], point_to_string(x),
                                          "the particle is outside the grid"));
      for (unsigned int d = 0; d < dim; ++d)
      {
        const unsigned int i = cell[d];
        const double xi      = (x[d] - grid.coordinates(d)[i]) / h[d];
        const double t       = 1 - xi;
        // Nodes i-1 .. i+2 at distances 1+xi, xi, 1-xi, 2-xi (in units of h).
        w[d]  = {{t * t * t / 6, 2. / 3 - xi * xi + 0.5 * xi * xi * xi,
                  2. / 3 - t * t + 0.5 * t * t * t, xi * xi * xi / 6}};
        dw[d] = {{-0.5 * t * t / h[d], (-2 * xi + 1.5 * xi * xi) / h[d],
                  (2 * t - 1.5 * t * t) / h[d], 0.5 * xi * xi / h[d]}};

        unsigned int lo = 0, hi = 3; // surviving slots
        const unsigned int n_1d = grid.n_nodes_in(d);
        if (i == 0) // node -1 missing: v_{-1} = 2 v_0 - v_1
        {
          w[d][1] += 2 * w[d][0], w[d][2] -= w[d][0];
          dw[d][1] += 2 * dw[d][0], dw[d][2] -= dw[d][0];
          lo = 1;
        }
        if (i + 2 >= n_1d) // node n missing: v_n = 2 v_{n-1} - v_{n-2}
        {
          w[d][2] += 2 * w[d][3], w[d][1] -= w[d][3];
          dw[d][2] += 2 * dw[d][3], dw[d][1] -= dw[d][3];
          hi = 2;
        }
        for (unsigned int k = lo; k <= hi; ++k)
          w[d][k - lo] = w[d][k], dw[d][k - lo] = dw[d][k];
        r.i0[d] = i + lo - 1;
        r.n[d]  = hi - lo + 1;
      }
      store_row(grid, conn, p, r);
    }
  }

private:
  const BackgroundGrid<dim> &grid;
  std::array<double, dim> h;
};
} // namespace shape_functions
} // namespace lme_mpm

using lme_mpm::shape_functions::BSpline;
LME_MPM_REGISTER_SHAPE_FUNCTION(BSpline, "bspline",
                                "cubic B-splines on the grid nodes (support 2h, C2); "
                                "uniform grids only, edge nodes extrapolated linearly.")
