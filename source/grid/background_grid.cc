#include <deal.II/grid/grid_generator.h>

#include <deal.II/fe/fe_q.h>

#include <lme_mpm/base/format.h>
#include <lme_mpm/base/input.h>
#include <lme_mpm/base/memory.h>
#include <lme_mpm/base/parameters.h>
#include <lme_mpm/grid/background_grid.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace lme_mpm
{
namespace
{
const char *axis_name[3] = {"x", "y", "z"};

/// "10*0.1, 5*0.05" -> ten steps of 0.1 then five of 0.05.
std::vector<double> parse_steps(const std::string &text, const std::string &entry)
{
  std::vector<double> steps;
  for (const auto &piece : input::split(text, ','))
  {
    const auto star   = piece.find('*');
    std::size_t count = 1;
    std::string size  = piece;
    if (star != std::string::npos)
    {
      const auto c = input::parse_doubles(piece.substr(0, star), entry);
      AssertThrow(c.size() == 1 && c[0] >= 1 && c[0] == std::floor(c[0]),
                  ExcBadInput(entry, "repeat count in '" + piece +
                                         "' must be a positive integer"));
      count = static_cast<std::size_t>(c[0]);
      size  = piece.substr(star + 1);
    }
    const auto h = input::parse_doubles(size, entry);
    AssertThrow(h.size() == 1 && h[0] > 0,
                ExcBadInput(entry, "step size in '" + piece + "' must be positive"));
    steps.insert(steps.end(), count, h[0]);
  }
  return steps;
}

/// The "Grid" entries, listed once for declaring and reading.
template <int dim>
struct GridEntries
{
  std::string lower, upper;
  double cell_size = 0.1;
  std::array<std::string, 3> steps;

  void entries(EntryList &list)
  {
    list.enter("Grid");
    list.add("Lower corner", lower, dim == 2 ? "0, 0" : "0, 0, 0", Patterns::Anything(),
             "Lower corner of the background grid (m).");
    list.add("Upper corner", upper, dim == 2 ? "1, 1" : "1, 1, 1", Patterns::Anything(),
             "Upper corner of the background grid (m).");
    list.add("Cell size", cell_size, "0.1", Patterns::Double(0),
             "Uniform cell size h (m); each extent must be a whole number of "
             "cells. Ignored in a direction that has its own step sizes.");
    for (unsigned int d = 0; d < 3; ++d)
      list.add(std::string("Step sizes ") + axis_name[d], steps[d], "",
               Patterns::Anything(),
               std::string("Graded spacing along ") + axis_name[d] +
                   ": comma-separated 'count*size' or 'size' items from the lower "
                   "corner (for example '10*0.01, 5*0.02'). Empty: uniform.");
    list.leave();
  }
};
} // namespace

template <int dim>
void BackgroundGrid<dim>::declare_parameters(ParameterHandler &prm)
{
  EntryList list(prm, EntryList::Mode::declare);
  GridEntries<dim>().entries(list);
}

template <int dim>
void BackgroundGrid<dim>::parse_parameters(ParameterHandler &prm)
{
  GridEntries<dim> in;
  EntryList list(prm, EntryList::Mode::parse);
  in.entries(list);
  const Point<dim> lo = input::parse_point<dim>(in.lower, "Grid/Lower corner");
  const Point<dim> hi = input::parse_point<dim>(in.upper, "Grid/Upper corner");
  const double h      = in.cell_size;
  {
    bool uniform_somewhere = false;
    for (unsigned int d = 0; d < dim; ++d)
      uniform_somewhere |= input::trim(in.steps[d]).empty();
    if (uniform_somewhere)
      AssertThrow(std::isfinite(h) && h > 0,
                  ExcBadInput("Grid/Cell size",
                              "must be positive (got " + format_double(h) +
                                  " m); it is used along every direction without "
                                  "'Grid/Step sizes'"));
  }
  // The size of the grid before any of it is allocated: a tiny cell size must stop
  // with what it would need, not exhaust the machine.
  {
    double cells      = 1;
    std::string entry = "Grid/Cell size";
    for (unsigned int d = 0; d < dim; ++d)
      if (input::trim(in.steps[d]).empty())
        cells *= std::max(1.0, std::round((hi[d] - lo[d]) / h));
      else
      {
        double count = 0;
        for (const auto &piece : input::split(in.steps[d], ','))
        {
          const auto star = piece.find('*');
          count += star == std::string::npos
                       ? 1.0
                       : std::abs(std::atof(piece.substr(0, star).c_str()));
        }
        cells *= std::max(1.0, count);
        entry = std::string("Grid/Step sizes ") + axis_name[d];
      }
    std::ostringstream what;
    what << "a grid of " << cells << " cells";
    // About 400 (2D) and 800 (3D) bytes per cell: deal.II's mesh and DoFs, the
    // nodal fields (measured on 2D grids of 2 and 4 million cells).
    memory::require(cells * (dim == 2 ? 400.0 : 800.0), entry, what.str());
  }
  std::array<std::vector<double>, dim> steps;
  for (unsigned int d = 0; d < dim; ++d)
  {
    const std::string entry = std::string("Grid/Step sizes ") + axis_name[d];
    AssertThrow(hi[d] > lo[d],
                ExcBadInput("Grid/Upper corner", "must exceed the lower corner in every "
                                                 "direction"));
    steps[d]      = parse_steps(in.steps[d], entry);
    double extent = 0;
    for (const double s : steps[d])
      extent += s;
    if (steps[d].empty())
    {
      const double n = (hi[d] - lo[d]) / h;
      if (!(std::abs(n - std::round(n)) < 1e-6 * std::max(1.0, n) && std::round(n) >= 1))
      {
        // Name the two whole numbers of cells either side of the request, so the
        // user can pick one (or move 'Grid/Upper corner').
        const double extent = hi[d] - lo[d];
        const double fewer  = std::max(1.0, std::floor(n));
        std::ostringstream msg;
        msg << h << " m does not divide the extent along " << axis_name[d] << " ("
            << extent
            << " m from 'Grid/Lower corner' to 'Grid/Upper corner') into a whole "
            << "number of cells (" << n << "); the nearest sizes that do are "
            << extent / (fewer + 1) << " m (" << fewer + 1 << " cells) and "
            << extent / fewer << " m (" << fewer << " cells)";
        throw ExcBadInput("Grid/Cell size", msg.str());
      }
      steps[d].assign(static_cast<std::size_t>(std::round(n)),
                      (hi[d] - lo[d]) / std::round(n));
    }
    else
      AssertThrow(std::abs(extent - (hi[d] - lo[d])) < 1e-9 * (hi[d] - lo[d]),
                  ExcBadInput(entry, "the steps do not add up to the grid extent"));
  }
  reinit(lo, steps);
}

template <int dim>
void BackgroundGrid<dim>::reinit(const Point<dim> &lower,
                                 const std::array<std::vector<double>, dim> &steps)
{
  h_min         = std::numeric_limits<double>::max();
  n_nodes_total = n_cells_total = 1;
  for (unsigned int d = 0; d < dim; ++d)
  {
    const auto [mn, mx]  = std::minmax_element(steps[d].begin(), steps[d].end());
    h_min                = std::min(h_min, *mn);
    uniform_h[d]         = (*mx - *mn <= 1e-12 * *mx) ? *mn : 0.0;
    inverse_uniform_h[d] = uniform_h[d] > 0 ? 1 / uniform_h[d] : 0.0;
    // Uniform directions as lower + i h, so the upper corner carries no summed
    // round-off.
    coords[d].assign(1, lower[d]);
    for (std::size_t i = 0; i < steps[d].size(); ++i)
      coords[d].push_back(uniform_h[d] > 0 ? lower[d] + (i + 1) * uniform_h[d]
                                           : coords[d].back() + steps[d][i]);
    node_strides[d] = n_nodes_total;
    cell_strides[d] = n_cells_total;
    n_nodes_total *= coords[d].size();
    n_cells_total *= steps[d].size();
  }
  h_max = 0;
  for (unsigned int d = 0; d < dim; ++d)
    for (std::size_t i = 0; i + 1 < coords[d].size(); ++i)
      h_max = std::max(h_max, spacing(d, i));
  for (unsigned int d = 0; d < dim; ++d)
  {
    bucket_cell[d].clear();
    inverse_bucket_width[d] = 0;
    if (uniform_h[d] > 0)
      continue;
    const auto &c      = coords[d];
    const double width = *std::min_element(steps[d].begin(), steps[d].end());
    const auto n       = static_cast<std::size_t>((c.back() - c.front()) / width) + 1;
    inverse_bucket_width[d] = 1 / width;
    for (std::size_t b = 0; b < n; ++b)
    {
      const double x = c.front() + b * width;
      const long k =
          static_cast<long>(std::upper_bound(c.begin(), c.end(), x) - c.begin()) - 1;
      bucket_cell[d].push_back(
          static_cast<unsigned int>(std::clamp<long>(k, 0, c.size() - 2)));
    }
  }

  std::vector<std::vector<double>> step_list(steps.begin(), steps.end());
  tria.clear();
  GridGenerator::subdivided_hyper_rectangle(tria, step_list, lower, upper_corner(),
                                            /*colorize=*/true);

  fe = std::make_unique<FESystem<dim>>(FE_Q<dim>(1), dim);
  dofs.reinit(tria);
  dofs.distribute_dofs(*fe);

  // Map the lexicographic node index to deal.II's vertex DoFs once, by position.
  node_to_dof.assign(n_nodes_total * dim, numbers::invalid_dof_index);
  std::vector<types::global_dof_index> cell_dofs(fe->n_dofs_per_cell());
  for (const auto &cell : dofs.active_cell_iterators())
  {
    cell->get_dof_indices(cell_dofs);
    for (const unsigned int v : cell->vertex_indices())
    {
      std::array<unsigned int, dim> ijk;
      const Point<dim> p = cell->vertex(v);
      for (unsigned int d = 0; d < dim; ++d)
      {
        const auto it =
            std::lower_bound(coords[d].begin(), coords[d].end(),
                             p[d] - 1e-10 * (coords[d].back() - coords[d].front()));
        ijk[d] = it - coords[d].begin();
      }
      const unsigned int node = node_index(ijk);
      for (unsigned int c = 0; c < dim; ++c)
        node_to_dof[node * dim + c] = cell_dofs[fe->component_to_system_index(c, v)];
    }
  }
}

template <int dim>
Point<dim> BackgroundGrid<dim>::lower_corner() const
{
  Point<dim> p;
  for (unsigned int d = 0; d < dim; ++d)
    p[d] = coords[d].front();
  return p;
}

template <int dim>
Point<dim> BackgroundGrid<dim>::upper_corner() const
{
  Point<dim> p;
  for (unsigned int d = 0; d < dim; ++d)
    p[d] = coords[d].back();
  return p;
}

template <int dim>
Point<dim> BackgroundGrid<dim>::node_point(unsigned int node) const
{
  Point<dim> p;
  for (unsigned int d = 0; d < dim; ++d)
  {
    p[d] = coords[d][node % coords[d].size()];
    node /= coords[d].size();
  }
  return p;
}

template <int dim>
std::vector<unsigned int>
BackgroundGrid<dim>::nodes_on_boundary(types::boundary_id id) const
{
  AssertThrow(id < 2 * dim, ExcBadInput("Boundary ids", "a Cartesian grid has ids 0.." +
                                                            std::to_string(2 * dim - 1)));
  const unsigned int d     = id / 2;
  const unsigned int layer = (id % 2 == 0) ? 0 : coords[d].size() - 1;
  std::vector<unsigned int> nodes;
  for (unsigned int n = 0; n < n_nodes_total; ++n)
    if ((n / node_strides[d]) % coords[d].size() == layer)
      nodes.push_back(n);
  return nodes;
}

template <int dim>
std::vector<unsigned int>
BackgroundGrid<dim>::nodes_in_box(const BoundingBox<dim> &box) const
{
  std::vector<unsigned int> nodes;
  const double tol = 1e-9 * (upper_corner() - lower_corner()).norm();
  for (unsigned int n = 0; n < n_nodes_total; ++n)
  {
    const Point<dim> p = node_point(n);
    bool in            = true;
    for (unsigned int d = 0; d < dim; ++d)
      in = in && p[d] >= box.get_boundary_points().first[d] - tol &&
           p[d] <= box.get_boundary_points().second[d] + tol;
    if (in)
      nodes.push_back(n);
  }
  return nodes;
}

template class BackgroundGrid<2>;
template class BackgroundGrid<3>;
} // namespace lme_mpm
