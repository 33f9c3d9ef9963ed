#include <deal.II/base/utilities.h>

#include <lme_mpm/simulation/halo_reach.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace lme_mpm
{
template <int dim>
HaloReach
halo_reach(const BackgroundGrid<dim> &grid, const ShapeFunction<dim> &shape_function,
           const FractureCoupling<dim> &fracture, const BodyContact<dim> &contact,
           const unsigned int mc, const unsigned int xpic)
{
  HaloReach reach;
  // In support radii; contact.reach() counts them too. XPIC(m) adds m - 1
  // consistent-mass products and an interpolation.
  const double supports = 4 + 4 * mc + (mc > 0 ? 1 : 0) + 2 * xpic + contact.reach(1.0);
  reach.support_passes  = static_cast<unsigned int>(std::ceil(supports / 2 - 1e-9));

  reach.node_radius.resize(grid.n_nodes());
  std::array<unsigned int, dim> ijk{};
  for (unsigned int a = 0; a < grid.n_nodes(); ++a)
  {
    reach.node_radius[a] = shape_function.node_support_radius(grid, ijk);
    for (unsigned int d = 0; d < dim && ++ijk[d] == grid.n_nodes_in(d); ++d)
      ijk[d] = 0;
  }

  if (fracture.active())
  {
    // A particle's fracture lengths follow the shortest side of the cell it started
    // in: the largest over the cell and its neighbours covers a particle that has
    // since moved into the next cell.
    reach.cell_radius.resize(grid.n_cells());
    ijk.fill(0);
    for (unsigned int c = 0; c < grid.n_cells(); ++c)
    {
      double h = 0;
      for (unsigned int k = 0; k < Utilities::pow(3u, dim); ++k)
      {
        double h_cell     = std::numeric_limits<double>::max();
        unsigned int code = k;
        for (unsigned int d = 0; d < dim; ++d, code /= 3)
        {
          const int i    = static_cast<int>(ijk[d]) + static_cast<int>(code % 3) - 1;
          const int last = static_cast<int>(grid.n_cells_in(d)) - 1;
          h_cell         = std::min(h_cell, grid.spacing(d, std::clamp(i, 0, last)));
        }
        h = std::max(h, h_cell);
      }
      reach.cell_radius[c] = fracture.reach_at(h);
      for (unsigned int d = 0; d < dim && ++ijk[d] == grid.n_cells_in(d); ++d)
        ijk[d] = 0;
    }
  }
  // Particles cross at most a fraction of a cell per step (the CFL limit); two cells
  // all round also keep the ghosts' own first neighbours complete.
  reach.margin_cells = 2;
  return reach;
}

template HaloReach halo_reach(const BackgroundGrid<2> &, const ShapeFunction<2> &,
                              const FractureCoupling<2> &, const BodyContact<2> &,
                              unsigned int, unsigned int);
template HaloReach halo_reach(const BackgroundGrid<3> &, const ShapeFunction<3> &,
                              const FractureCoupling<3> &, const BodyContact<3> &,
                              unsigned int, unsigned int);
} // namespace lme_mpm
