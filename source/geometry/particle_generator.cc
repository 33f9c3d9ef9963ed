#include <deal.II/base/parsed_function.h>
#include <deal.II/base/quadrature_lib.h>

#include <lme_mpm/base/format.h>
#include <lme_mpm/base/input.h>
#include <lme_mpm/base/memory.h>
#include <lme_mpm/base/parameters.h>
#include <lme_mpm/geometry/geometry.h>
#include <lme_mpm/geometry/particle_generator.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <sstream>

namespace lme_mpm
{
namespace
{
/// Calls f(ijk) for every multi-index in the box [lo, hi] (inclusive), first index
/// fastest.
template <int dim, class F>
void for_each_index(const std::array<unsigned int, dim> &lo,
                    const std::array<unsigned int, dim> &hi, const F &f)
{
  std::array<unsigned int, dim> ijk = lo;
  while (true)
  {
    f(ijk);
    unsigned int d = 0;
    while (d < dim && ++ijk[d] > hi[d])
      ijk[d] = lo[d], ++d;
    if (d == dim)
      break;
  }
}

/// A body's Shape before the file sets it.
template <int dim>
const char *default_shape_text()
{
  return dim == 2 ? "rectangle(0, 0, 1, 1)" : "rectangle(0, 0, 0, 1, 1, 1)";
}

/// The entries of one "Body N", listed once for declaring and reading; the
/// initial velocity is a ParsedFunction subsection beside them.
template <int dim>
struct BodyEntries
{
  unsigned int material = 1, particles_per_cell = 2;
  std::string shape, holes, placement, zones, surface;

  void entries(EntryList &list)
  {
    list.add("Surface", surface, "particles", Patterns::Selection("particles|exact"),
             "How a body that moves as prescribed (Prescribed velocity) meets the "
             "others. 'particles': it is filled with particles and touches the others "
             "through multi-field contact at the grid's nodes. 'exact': it has no "
             "particles; the exact surface of its Shape (rectangle, disc or cylinder, "
             "minus its Holes of the same kinds) moves rigidly and pushes each particle "
             "of the other bodies by "
             "a penalty on the gap between the particle's domain and the surface, so "
             "that the contact grows continuously inside a cell (doc/contact.md). "
             "Needs a Prescribed velocity; not Contact/Type = multi-field.");
    list.add("Material", material, "1", Patterns::Integer(1),
             "Number N of the 'Material N' the body is made of.");
    list.add("Shape", shape, default_shape_text<dim>(), Patterns::Anything(),
             "Region the body fills: " +
                 GeometryRegistry<dim>::instance().documentation());
    list.add("Holes", holes, "", Patterns::Anything(),
             "Regions removed from the shape (notches, holes), separated by "
             "';', in the same form as 'Shape'.");
    list.add("Material zones", zones, "", Patterns::Anything(),
             "Regions of the body made of another material, 'M: shape' separated "
             "by ';' (M the number of a 'Material N', the shape in the form of "
             "'Shape'); a later zone wins where zones overlap. The body stays one "
             "body (one velocity field, one fracture neighbourhood): for example "
             "concrete kept elastic where a support or a strip presses it.");
    list.add("Particle placement", placement, "gauss",
             Patterns::Selection("gauss|uniform"),
             "'gauss': particles at the Gauss points of each cell (the paper's "
             "choice); 'uniform': at the centres of equal sub-cells, so that "
             "particle boxes tile the body (what uGIMP assumes).");
    list.add("Particles per cell direction", particles_per_cell, "2",
             Patterns::Integer(1, 8),
             "Particles at the Gauss points of each background cell, this "
             "many per direction.");
  }
};
} // namespace

template <int dim>
void ParticleGenerator<dim>::declare_parameters(ParameterHandler &prm,
                                                const unsigned int n_bodies)
{
  EntryList list(prm, EntryList::Mode::declare);
  for (unsigned int b = 0; b < n_bodies; ++b)
  {
    prm.enter_subsection(input::subsection_name("Body", b));
    BodyEntries<dim>().entries(list);
    prm.enter_subsection("Initial velocity");
    Functions::ParsedFunction<dim>::declare_parameters(prm, dim);
    prm.leave_subsection();
    prm.leave_subsection();
  }
}

namespace
{
/// One body as its entries describe it: where it is and what it is made of.
template <int dim>
struct BodyInput
{
  BodyPlacement placement;
  std::unique_ptr<Geometry<dim>> shape;
  std::vector<std::unique_ptr<Geometry<dim>>> holes;
  /// Material zones: material index and region, later ones winning.
  std::vector<std::pair<unsigned int, std::unique_ptr<Geometry<dim>>>> zones;
  bool uniform = false;
  /// Surface = exact: a rigid surface, no particles.
  bool exact = false;
  /// Shape left at its declared default: usually a body the file never describes.
  bool default_shape = false;
  std::unique_ptr<Functions::ParsedFunction<dim>> velocity;
};

/// Reads "Body @p b" (entered by the caller); throws ExcBadInput naming the entry.
template <int dim>
BodyInput<dim> read_body(ParameterHandler &prm, const std::string &section,
                         const std::size_t n_materials)
{
  const auto &geometries = GeometryRegistry<dim>::instance();
  BodyInput<dim> body;
  BodyPlacement &placement = body.placement;
  placement.section        = section;
  BodyEntries<dim> in;
  EntryList list(prm, EntryList::Mode::parse);
  in.entries(list);
  placement.material = in.material - 1;
  body.exact         = in.surface == "exact";
  AssertThrow(placement.material < n_materials,
              ExcBadInput(section + "/Material",
                          "must be between 1 and Problem/Number of materials = " +
                              std::to_string(n_materials)));
  body.default_shape = input::trim(in.shape) == default_shape_text<dim>();
  body.shape         = geometries.create(in.shape, section + "/Shape");
  for (const auto &h : input::split(in.holes, ';'))
    body.holes.push_back(geometries.create(h, section + "/Holes"));
  for (const auto &z : input::split(in.zones, ';'))
  {
    const std::string entry = section + "/Material zones";
    const auto colon        = z.find(':');
    AssertThrow(colon != std::string::npos,
                ExcBadInput(entry, "'" + z + "' is not of the form 'M: shape'"));
    const std::string number = input::trim(z.substr(0, colon));
    char *end                = nullptr;
    const long m             = std::strtol(number.c_str(), &end, 10);
    AssertThrow(!number.empty() && *end == '\0' && m >= 1 &&
                    static_cast<std::size_t>(m) <= n_materials,
                ExcBadInput(entry, "'" + number +
                                       "' must be the number of a material, 1 to "
                                       "Problem/Number of materials = " +
                                       std::to_string(n_materials)));
    body.zones.emplace_back(static_cast<unsigned int>(m - 1),
                            geometries.create(z.substr(colon + 1), entry));
    placement.zone_materials.push_back(static_cast<unsigned int>(m - 1));
  }
  placement.particles_per_cell = in.particles_per_cell;
  body.uniform                 = in.placement == "uniform";
  body.velocity                = std::make_unique<Functions::ParsedFunction<dim>>(dim);
  input::parse_function(prm, "Initial velocity", *body.velocity,
                        section + "/Initial velocity");
  return body;
}

/// Throws unless the body's shape lies inside the grid (or part of it would silently
/// vanish); returns its bounding box.
template <int dim>
std::pair<Point<dim>, Point<dim>> check_inside_grid(const BodyInput<dim> &body,
                                                    const BackgroundGrid<dim> &grid)
{
  const double tol = 1e-9 * (grid.upper_corner() - grid.lower_corner()).norm();
  const auto box   = body.shape->bounding_box().get_boundary_points();
  for (unsigned int d = 0; d < dim; ++d)
    if (box.first[d] > -1e299 && !(box.first[d] >= grid.lower_corner()[d] - tol &&
                                   box.second[d] <= grid.upper_corner()[d] + tol))
    {
      const std::string &section = body.placement.section;
      std::ostringstream msg;
      if (body.default_shape)
        msg << "is left at its default '" << default_shape_text<dim>()
            << "', which lies outside the grid: 'Problem/Number of bodies' asks for a '"
            << section << "' that the file does not describe (give it a subsection "
            << "with a Shape, or lower the number of bodies)";
      else
        msg << "the body spans " << box.first[d] << " to " << box.second[d] << " m along "
            << "xyz"[d] << ", beyond the background grid's " << grid.lower_corner()[d]
            << " to " << grid.upper_corner()[d]
            << " m ('Grid/Lower corner' and 'Grid/Upper corner'): enlarge the grid or "
            << "move the body";
      throw ExcBadInput(section + "/Shape", msg.str());
    }
  return box;
}

/**
 * Adds the particles of @p body (number @p b) at the quadrature points of the
 * background cells that overlap its box and lie inside it, and records where they
 * sit in their cells.
 */
template <int dim>
void place_particles(BodyInput<dim> &body, const unsigned int b,
                     const BackgroundGrid<dim> &grid,
                     const std::vector<double> &densities, const double thickness,
                     ParticleStore<dim> &store)
{
  BodyPlacement &placement = body.placement;
  const QGauss<1> gauss_rule(placement.particles_per_cell);
  const QIterated<1> uniform_rule(QMidpoint<1>(), placement.particles_per_cell);
  const Quadrature<1> &rule = body.uniform
                                  ? static_cast<const Quadrature<1> &>(uniform_rule)
                                  : static_cast<const Quadrature<1> &>(gauss_rule);
  const std::size_t before  = store.size();
  placement.cells.assign(grid.n_cells(), 0);
  placement.offsets.clear();
  placement.weights.clear();
  for (unsigned int q = 0; q < rule.size(); ++q)
  {
    placement.offsets.push_back(rule.point(q)[0]);
    placement.weights.push_back(rule.weight(q));
  }
  // A rigid exact surface has no particles and may reach outside the grid.
  if (body.exact)
  {
    AssertThrow(body.zones.empty(),
                ExcBadInput(placement.section + "/Surface",
                            "'exact' is one rigid surface: leave Material zones empty"));
    return;
  }
  const auto box = check_inside_grid(body, grid);
  std::array<unsigned int, dim> lo, hi, q_lo{}, q_hi;
  for (unsigned int d = 0; d < dim; ++d)
  {
    grid.locate(std::max(box.first[d], grid.coordinates(d).front()), d, lo[d]);
    grid.locate(std::min(box.second[d], grid.coordinates(d).back()), d, hi[d]);
    q_hi[d] = placement.particles_per_cell - 1;
  }
  {
    // At most this many particles, before any is allocated (about 600 bytes each
    // in 2D and 900 in 3D with their connectivity, measured on linear functions).
    double candidates = 1;
    for (unsigned int d = 0; d < dim; ++d)
      candidates *= double(hi[d] - lo[d] + 1) * placement.particles_per_cell;
    std::ostringstream what;
    what << "up to " << candidates << " particles";
    memory::require((store.size() + candidates) * (dim == 2 ? 600.0 : 900.0),
                    placement.section + "/Particles per cell direction", what.str());
  }
  for_each_index<dim>(
      lo, hi,
      [&](const std::array<unsigned int, dim> &ijk)
      {
        for_each_index<dim>(
            q_lo, q_hi,
            [&](const std::array<unsigned int, dim> &q)
            {
              Point<dim> x;
              double volume = dim == 2 ? thickness : 1.0;
              for (unsigned int d = 0; d < dim; ++d)
              {
                const double h = grid.spacing(d, ijk[d]);
                x[d]           = grid.coordinates(d)[ijk[d]] + h * rule.point(q[d])[0];
                volume *= h * rule.weight(q[d]);
              }
              bool keep = body.shape->inside(x);
              for (const auto &h : body.holes)
                keep = keep && !h->inside(x);
              if (!keep)
                return;
              unsigned int material = placement.material;
              for (const auto &zone : body.zones)
                if (zone.second->inside(x))
                  material = zone.first;
              const double rho = densities[material];
              AssertThrow(std::isfinite(rho * volume) && rho * volume > 0,
                          ExcBadInput(placement.section,
                                      "a particle's volume " + format_double(volume) +
                                          " m^3 and mass " + format_double(rho * volume) +
                                          " kg (from the cell size, Problem/Thickness "
                                          "and the material's Density) must be "
                                          "finite and positive"));
              const std::size_t p = store.add(x, rho * volume, volume, material, b);
              placement.cells[grid.cell_index(ijk)] = 1;
              for (unsigned int d = 0; d < dim; ++d)
              {
                store.velocity[p][d] = body.velocity->value(x, d);
                AssertThrow(std::isfinite(store.velocity[p][d]),
                            ExcBadInput(placement.section + "/Initial velocity",
                                        "is not finite at " + point_to_string(x)));
              }
            });
      });
  AssertThrow(store.size() > before,
              ExcBadInput(placement.section + "/Shape",
                          "the body holds no particle: it is smaller than a cell or "
                          "fully cut away"));
}
} // namespace

template <int dim>
std::vector<BodyPlacement>
ParticleGenerator<dim>::fill(ParameterHandler &prm, const unsigned int n_bodies,
                             const BackgroundGrid<dim> &grid,
                             const std::vector<double> &densities, const double thickness,
                             ParticleStore<dim> &store)
{
  std::vector<BodyPlacement> bodies;
  for (unsigned int b = 0; b < n_bodies; ++b)
  {
    const std::string section = input::subsection_name("Body", b);
    prm.enter_subsection(section);
    BodyInput<dim> body = read_body<dim>(prm, section, densities.size());
    prm.leave_subsection();
    place_particles(body, b, grid, densities, thickness, store);
    bodies.push_back(std::move(body.placement));
  }
  for (std::size_t p = 0; p < store.size(); ++p)
    store.id[p] = static_cast<std::uint32_t>(p);
  return bodies;
}

template class ParticleGenerator<2>;
template class ParticleGenerator<3>;
} // namespace lme_mpm
