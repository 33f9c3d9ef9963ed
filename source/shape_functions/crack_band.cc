#include <lme_mpm/shape_functions/crack_band.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>

namespace lme_mpm
{
template <int dim>
CrackBand crack_band(const ShapeFunction<dim> &functions, const BackgroundGrid<dim> &grid,
                     const std::vector<double> &offsets,
                     const std::vector<double> &weights, const double thickness)
{
  Assert(!offsets.empty() && weights.size() == offsets.size(), ExcInternalError());
  std::array<unsigned int, dim> middle;
  for (unsigned int d = 0; d < dim; ++d)
    middle[d] = grid.n_cells_in(d) / 2;
  const unsigned int k = offsets.size();

  CrackBand band{0, 0};
  unsigned int directions = 0;
  for (unsigned int d = 0; d < dim; ++d)
  {
    if (grid.n_cells_in(d) < 2)
      continue;
    // Particles of the middle cell and of up to three cells on either side along d.
    const unsigned int first = middle[d] >= 3 ? middle[d] - 3 : 0,
                       last  = std::min(middle[d] + 3, grid.n_cells_in(d) - 1);
    unsigned int per_cell    = 1;
    for (unsigned int e = 0; e < dim; ++e)
      per_cell *= k;
    ParticleStore<dim> probe;
    std::vector<bool> in_middle;
    for (unsigned int c = first; c <= last; ++c)
      for (unsigned int i = 0; i < per_cell; ++i)
      {
        Point<dim> x;
        double volume = dim == 2 ? thickness : 1.0;
        for (unsigned int e = 0, j = i; e < dim; ++e, j /= k)
        {
          const unsigned int cell = e == d ? c : middle[e];
          const double h          = grid.spacing(e, cell);
          x[e]                    = grid.coordinates(e)[cell] + offsets[j % k] * h;
          volume *= weights[j % k] * h;
        }
        const std::size_t p = probe.add(x, volume, volume, 0, 0);
        probe.id[p]         = p;
        in_middle.push_back(c == middle[d]);
      }
    const std::size_t n = probe.size();
    Connectivity<dim> conn;
    conn.resize(n, functions.max_nodes_per_particle());
    functions.compute(probe, 0, n, conn);

    // The jump lies between the node planes of the middle cell: nodes at or beyond
    // plane middle + 1 move with it.
    const unsigned int stride = grid.node_stride(d), plane = middle[d] + 1;
    std::vector<double> g(n, 0.0);
    double g_max = 0;
    for (std::size_t p = 0; p < n; ++p)
    {
      for (unsigned int s = 0; s < conn.n_nodes[p]; ++s)
      {
        const unsigned int node = conn.nodes[p * conn.stride + s];
        if ((node / stride) % grid.n_nodes_in(d) >= plane)
          g[p] += conn.grad_N[p * conn.stride + s][d];
      }
      if (in_middle[p])
        g_max = std::max(g_max, g[p]);
    }
    AssertThrow(g_max > 0,
                ExcMessage(functions.name() + " shape functions: a jump of the nodal "
                                              "displacements strains no particle"));
    const double h = grid.spacing(d, middle[d]);
    double reach   = 0;
    for (std::size_t p = 0; p < n; ++p)
      if (g[p] >= 0.01 * g_max)
      {
        double nearest = std::numeric_limits<double>::max();
        for (std::size_t q = 0; q < n; ++q)
          if (g[q] >= g_max * (1 - 1e-9))
            nearest =
                std::min(nearest, std::abs(probe.position[p][d] - probe.position[q][d]));
        reach = std::max(reach, nearest);
      }
    band.width_cells += 1 / (g_max * h);
    band.reach_cells += reach / h;
    ++directions;
  }
  if (directions == 0)
    return CrackBand{};
  band.width_cells /= directions;
  band.reach_cells /= directions;
  return band;
}

template <int dim>
std::vector<CrackBand>
crack_bands(const ShapeFunction<dim> &functions, const BackgroundGrid<dim> &grid,
            const std::vector<CellPlacement> &placements, const double thickness)
{
  std::map<CellPlacement, CrackBand> measured;
  std::vector<CrackBand> bands;
  for (const auto &placement : placements)
  {
    auto it = measured.find(placement);
    if (it == measured.end())
      it = measured
               .emplace(placement, crack_band(functions, grid, placement.first,
                                              placement.second, thickness))
               .first;
    bands.push_back(it->second);
  }
  return bands;
}

template std::vector<CrackBand> crack_bands<2>(const ShapeFunction<2> &,
                                               const BackgroundGrid<2> &,
                                               const std::vector<CellPlacement> &,
                                               double);
template std::vector<CrackBand> crack_bands<3>(const ShapeFunction<3> &,
                                               const BackgroundGrid<3> &,
                                               const std::vector<CellPlacement> &,
                                               double);
template CrackBand crack_band<2>(const ShapeFunction<2> &, const BackgroundGrid<2> &,
                                 const std::vector<double> &, const std::vector<double> &,
                                 double);
template CrackBand crack_band<3>(const ShapeFunction<3> &, const BackgroundGrid<3> &,
                                 const std::vector<double> &, const std::vector<double> &,
                                 double);
} // namespace lme_mpm
