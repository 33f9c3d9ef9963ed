#include <lme_mpm/base/format.h>
#include <lme_mpm/shape_functions/tensor_product.h>

#include <cmath>
#include <sstream>

namespace lme_mpm
{
namespace shape_functions
{
/**
 * Uniform GIMP (Bardenhagen & Kober 2004): each particle is a box of half-width lp
 * (its initial volume, undeformed) and its weight for node I is the mean of the
 * nodal hat function over that box. Smoothing the hat over the particle domain makes
 * the gradients continuous when a particle crosses a cell face, which removes the
 * cell-crossing noise of linear MPM at the cost of 3 nodes per direction instead of
 * 2. Averages are taken with the hat's antiderivative, so graded grids need no
 * special treatment. A box that overhangs the grid edge (particles seeded at Gauss
 * points near a boundary do, by up to 0.04 h) is clipped to the grid: the weights still
 * sum to one, and reproduce the centre of the clipped box; only a particle whose
 * centre leaves the grid is an error.
 */
template <int dim>
class UGIMP : public ShapeFunction<dim>
{
public:
  /// Compile-time bound on nodes per direction (array size of the 1D weights).
  static constexpr unsigned int max_1d = 4;

  static void declare_parameters(ParameterHandler &) {}

  UGIMP(ParameterHandler &, const ShapeFunctionContext<dim> &context)
      : grid(*context.grid), thickness(context.thickness)
  {
    AssertThrow(thickness > 0, ExcMessage("uGIMP needs a positive 2D thickness."));
    // A box no wider than its cell covers at most 2 cells (3 nodes) of a uniform
    // direction; at a change of spacing it can reach a third cell.
    max_nodes = 1;
    for (unsigned int d = 0; d < dim; ++d)
    {
      n_max[d] = grid.is_uniform(d) ? 3 : max_1d;
      max_nodes *= n_max[d];
    }
  }

  std::string name() const override { return "ugimp"; }
  unsigned int max_nodes_per_particle() const override { return max_nodes; }
  unsigned int factor_width() const override { return max_1d; }
  double support_radius(const BackgroundGrid<dim> &g) const override
  {
    // h plus the box half-width (at most h / 2) per direction; a box reaching a
    // third cell of a graded direction is within two cells.
    bool uniform = true;
    for (unsigned int d = 0; d < dim; ++d)
      uniform = uniform && g.is_uniform(d);
    return (uniform ? 1.5 : 2.0) * this->largest_cell_diagonal(g);
  }
  double node_support_radius(const BackgroundGrid<dim> &g,
                             const std::array<unsigned int, dim> &node) const override
  {
    bool uniform = true;
    for (unsigned int d = 0; d < dim; ++d)
      uniform = uniform && g.is_uniform(d);
    return (uniform ? 1.5 : 2.0) * this->cell_diagonal_near(g, node, 2);
  }

  void compute(ParticleStore<dim> &particles, const std::size_t begin,
               const std::size_t end, Connectivity<dim> &conn) const override
  {
    Assert(conn.factor_width == max_1d || conn.stride >= max_nodes, ExcInternalError());
    for (std::size_t p = begin; p < end; ++p)
    {
      const Point<dim> &x = particles.position[p];
      const double v0     = particles.initial_volume[p];
      const double lp     = 0.5 * (dim == 2 ? std::sqrt(v0 / thickness) : std::cbrt(v0));
      const auto fail     = [&](const std::string &reason)
      {
        AssertThrow(false, ExcShapeFunctionFailure("ugimp", particles.id[p],
                                                   point_to_string(x), reason));
      };
      if (!(lp > 0))
        fail("the particle has no volume, so no GIMP domain");

      SeparableRow<dim, max_1d> r;
      auto &i0 = r.i0, &n = r.n;
      auto &w = r.w, &dw = r.dw;
      for (unsigned int d = 0; d < dim; ++d)
      {
        const std::vector<double> &c = grid.coordinates(d);
        double a = x[d] - lp, b = x[d] + lp;
        // The box may overhang the grid edge and is clipped; the centre may not.
        if (!(x[d] >= c.front() && x[d] <= c.back()))
        {
          std::ostringstream s;
          s << "the particle domain [" << a << ", " << b << "] (half-width " << lp
            << ") has its centre outside the grid [" << c.front() << ", " << c.back()
            << "] along direction " << d;
          fail(s.str());
        }
        a = std::max(a, c.front());
        b = std::min(b, c.back());

        // Nodes I with (x_{I-1}, x_{I+1}) overlapping (a, b).
        unsigned int ca, cb;
        grid.locate(a, d, ca);
        grid.locate(b, d, cb);
        const unsigned int first = ca;
        const unsigned int last  = (c[cb] < b) ? cb + 1 : cb;
        if (last - first + 1 > n_max[d])
        {
          std::ostringstream s;
          s << "the particle domain (half-width " << lp << ") covers " << last - first + 1
            << " nodes along direction " << d << ", more than the " << n_max[d]
            << " uGIMP allows; the particles are larger than the grid cells";
          fail(s.str());
        }
        i0[d]              = first;
        n[d]               = last - first + 1;
        const double width = b - a; // 2 lp unless clipped at the grid edge
        for (unsigned int k = 0; k < n[d]; ++k)
        {
          const unsigned int I = first + k;
          w[d][k]  = (antiderivative(c, I, b) - antiderivative(c, I, a)) / width;
          dw[d][k] = (hat(c, I, b) - hat(c, I, a)) / width;
        }
      }
      store_row(grid, conn, p, r);
    }
  }

private:
  /// Hat function of node I on coordinates c, at s inside the grid.
  static double hat(const std::vector<double> &c, const unsigned int I, const double s)
  {
    if (s < c[I])
      return (I > 0 && s > c[I - 1]) ? (s - c[I - 1]) / (c[I] - c[I - 1]) : 0.0;
    if (I + 1 == c.size())
      return 1.0; // s is the upper grid edge
    return (s < c[I + 1]) ? (c[I + 1] - s) / (c[I + 1] - c[I]) : 0.0;
  }

  /// Integral of the hat of node I from the lower grid edge to s.
  static double antiderivative(const std::vector<double> &c, const unsigned int I,
                               const double s)
  {
    const double left = (I > 0) ? c[I - 1] : c[I];
    if (s <= left)
      return 0.0;
    if (s <= c[I])
      return (s - left) * (s - left) / (2 * (c[I] - left));
    const double left_area = 0.5 * (c[I] - left);
    if (I + 1 == c.size())
      return left_area;
    const double hp = c[I + 1] - c[I];
    if (s >= c[I + 1])
      return left_area + 0.5 * hp;
    const double t = c[I + 1] - s;
    return left_area + 0.5 * hp - t * t / (2 * hp);
  }

  const BackgroundGrid<dim> &grid;
  const double thickness;
  std::array<unsigned int, dim> n_max;
  unsigned int max_nodes;
};
} // namespace shape_functions
} // namespace lme_mpm

using lme_mpm::shape_functions::UGIMP;
LME_MPM_REGISTER_SHAPE_FUNCTION(UGIMP, "ugimp",
                                "uniform GIMP: nodal hat functions averaged over the "
                                "particle's undeformed box (Bardenhagen & Kober 2004); "
                                "continuous gradients, 3 nodes per direction.")
