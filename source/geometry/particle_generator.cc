#include <deal.II/base/parsed_function.h>
#include <deal.II/base/quadrature_lib.h>

#include <lme_mpm/base/format.h>
#include <lme_mpm/base/input.h>
#include <lme_mpm/base/memory.h>
#include <lme_mpm/base/parameters.h>
#include <lme_mpm/geometry/geometry.h>
#include <lme_mpm/geometry/particle_generator.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
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
  std::string shape, holes, placement, zones, surface, particle_file;

  void entries(EntryList &list)
  {
    list.add("Surface", surface, "particles", Patterns::Selection("particles|exact"),
             "How a body that moves as prescribed (Prescribed velocity) meets the "
             "others. 'particles': it is filled with particles and touches the others "
             "through multi-field contact at the grid's nodes. 'exact': it has no "
             "particles; the exact surface of its Shape (rectangle, disc, cylinder, "
             "polygon or 2D mesh, minus its Holes of the same kinds) moves rigidly and "
             "pushes each particle "
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
    list.add("Particle file", particle_file, "", Patterns::Anything(),
             "A CSV file of the body's particles, read instead of filling the "
             "Shape (leave Shape at its default): a header line naming the columns, "
             "then one particle per line. Columns: x, y (and z in 3D) in m; volume "
             "in m^3 (in 2D the area times Problem/Thickness) or, in 2D, area in "
             "m^2; optional material (the number N of a 'Material N', else the "
             "body's Material and Material zones); optional vx, vy (and vz) in m/s "
             "(else the Initial velocity). Lines starting with '#' are skipped. "
             "Holes cut the file's particles as they cut a shape. A path relative "
             "to the working directory.");
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
  /// A CSV file of particles read instead of filling the shape.
  std::string particle_file;
  std::unique_ptr<Functions::ParsedFunction<dim>> velocity;

  /// Whether a point lies in none of the holes.
  bool outside_holes(const Point<dim> &x) const
  {
    return std::none_of(holes.begin(), holes.end(),
                        [&x](const auto &h) { return h->inside(x); });
  }
  /// The material at @p x: the body's, or that of the last zone holding it.
  unsigned int material_at(const Point<dim> &x) const
  {
    unsigned int material = placement.material;
    for (const auto &zone : zones)
      if (zone.second->inside(x))
        material = zone.first;
    return material;
  }
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
  body.particle_file           = input::trim(in.particle_file);
  if (!body.particle_file.empty())
  {
    AssertThrow(body.default_shape,
                ExcBadInput(section + "/Shape",
                            "is set, and so is '" + section + "/Particle file' = '" +
                                body.particle_file +
                                "': a body's particles come from one of them; leave "
                                "the other out"));
    AssertThrow(!body.exact,
                ExcBadInput(section + "/Surface", "'exact' has no particles: leave '" +
                                                      section + "/Particle file' empty"));
  }
  body.velocity = std::make_unique<Functions::ParsedFunction<dim>>(dim);
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

/// One particle file's columns, by their header names.
struct ParticleColumns
{
  std::vector<int> position, velocity;
  int volume = -1, area = -1, material = -1;
  std::size_t count = 0;
};

template <int dim>
ParticleColumns read_header(const std::string &line, const std::string &entry,
                            const std::string &file)
{
  ParticleColumns c;
  const auto names = input::split(line, ',');
  c.count          = names.size();
  const auto find  = [&](const std::string &name)
  {
    for (std::size_t i = 0; i < names.size(); ++i)
      if (names[i] == name)
        return static_cast<int>(i);
    return -1;
  };
  const char *axes = "xyz";
  for (unsigned int d = 0; d < dim; ++d)
  {
    c.position.push_back(find(std::string(1, axes[d])));
    c.velocity.push_back(find(std::string("v") + axes[d]));
  }
  c.volume   = find("volume");
  c.area     = dim == 2 ? find("area") : -1;
  c.material = find("material");
  const bool positions =
      std::find(c.position.begin(), c.position.end(), -1) == c.position.end();
  const long velocities = std::count(c.velocity.begin(), c.velocity.end(), -1);
  AssertThrow(positions && (c.volume >= 0) != (c.area >= 0) &&
                  (velocities == 0 || velocities == dim),
              ExcBadInput(entry, "the header of '" + file + "' is '" + line +
                                     "'; it must name the columns " +
                                     (dim == 2 ? "x, y" : "x, y, z") + " and " +
                                     (dim == 2 ? "one of volume or area" : "volume") +
                                     ", optionally material and " +
                                     (dim == 2 ? "vx, vy" : "vx, vy, vz") +
                                     " (all velocity components or none)"));
  return c;
}

/// The fractions of a cell at which @p n particles per direction sit, and their
/// volumes' shares, recognised as the Gauss or uniform rule from @p seen (the
/// distinct fractions along x of a file's particles), else the uniform rule.
void recognise_rule(const std::vector<double> &seen, const unsigned int n,
                    BodyPlacement &placement)
{
  const QGauss<1> gauss(n);
  const QIterated<1> uniform(QMidpoint<1>(), n);
  const Quadrature<1> *rule = &uniform;
  if (seen.size() == n)
  {
    bool is_gauss = true;
    for (unsigned int q = 0; q < n; ++q)
      is_gauss = is_gauss && std::abs(seen[q] - gauss.point(q)[0]) < 1e-6;
    if (is_gauss)
      rule = &gauss;
  }
  placement.offsets.clear();
  placement.weights.clear();
  for (unsigned int q = 0; q < n; ++q)
  {
    placement.offsets.push_back(rule->point(q)[0]);
    placement.weights.push_back(rule->weight(q));
  }
}

/**
 * Adds the particles of body @p b from its particle file: positions inside the grid,
 * volumes positive, materials of the set. Its particles per cell direction come from
 * their mean spacing, and where they sit in their cells from their positions, for the
 * rules (the crack band, the neighbourhood check) that depend on them.
 */
template <int dim>
void read_particle_file(BodyInput<dim> &body, const unsigned int b,
                        const BackgroundGrid<dim> &grid,
                        const std::vector<double> &densities, const double thickness,
                        ParticleStore<dim> &store)
{
  BodyPlacement &placement = body.placement;
  const std::string entry  = placement.section + "/Particle file";
  const std::string &file  = body.particle_file;
  std::ifstream in(file);
  AssertThrow(in, ExcBadInput(entry, "cannot open '" + file +
                                         "' (a path relative to the working directory)"));
  placement.cells.assign(grid.n_cells(), 0);
  const std::size_t before = store.size();
  ParticleColumns columns;
  bool header = false;
  std::string line;
  double spacing_sum = 0;
  std::vector<double> fractions;
  for (unsigned int line_number = 1; std::getline(in, line); ++line_number)
  {
    const std::string t = input::trim(line);
    if (t.empty() || t[0] == '#')
      continue;
    if (!header)
    {
      columns = read_header<dim>(t, entry, file);
      header  = true;
      continue;
    }
    const std::string where =
        "line " + std::to_string(line_number) + " of '" + file + "'";
    std::vector<double> v;
    try
    {
      v = input::parse_doubles(t, entry);
    }
    catch (const ExcBadInput &)
    {
      AssertThrow(false, ExcBadInput(entry, where +
                                                " holds a value that is not a "
                                                "finite number: '" +
                                                t + "'"));
    }
    AssertThrow(v.size() == columns.count,
                ExcBadInput(entry, where + " holds " + std::to_string(v.size()) +
                                       " values where the header names " +
                                       std::to_string(columns.count)));
    Point<dim> x;
    for (unsigned int d = 0; d < dim; ++d)
      x[d] = v[columns.position[d]];
    std::array<unsigned int, dim> ijk;
    AssertThrow(grid.locate(x, ijk),
                ExcBadInput(entry, where + " places a particle at " + point_to_string(x) +
                                       ", outside the background grid ('Grid/Lower "
                                       "corner' and 'Grid/Upper corner')"));
    const double volume =
        columns.volume >= 0 ? v[columns.volume] : v[columns.area] * thickness;
    AssertThrow(volume > 0,
                ExcBadInput(entry, where + " gives the volume " + format_double(volume) +
                                       " m^3; it must be positive"));
    if (!body.outside_holes(x))
      continue;
    unsigned int material = body.material_at(x);
    if (columns.material >= 0)
    {
      const double m = v[columns.material];
      AssertThrow(m == std::round(m) && m >= 1 && m <= densities.size(),
                  ExcBadInput(entry, where + " gives the material " + format_double(m) +
                                         "; it must be the number of a material, 1 "
                                         "to Problem/Number of materials = " +
                                         std::to_string(densities.size())));
      material = static_cast<unsigned int>(m) - 1;
    }
    const std::size_t p = store.add(x, densities[material] * volume, volume, material, b);
    for (unsigned int d = 0; d < dim; ++d)
      store.velocity[p][d] =
          columns.velocity[0] >= 0 ? v[columns.velocity[d]] : body.velocity->value(x, d);
    placement.cells[grid.cell_index(ijk)] = 1;
    const double extent = dim == 2 ? std::sqrt(volume / thickness) : std::cbrt(volume);
    spacing_sum += extent / grid.spacing(0, ijk[0]);
    if (fractions.size() < 64)
    {
      const double f = (x[0] - grid.coordinates(0)[ijk[0]]) / grid.spacing(0, ijk[0]);
      if (std::none_of(fractions.begin(), fractions.end(),
                       [f](const double g) { return std::abs(f - g) < 1e-6; }))
        fractions.push_back(f);
    }
  }
  AssertThrow(header, ExcBadInput(entry, "'" + file + "' holds no header line"));
  const std::size_t added = store.size() - before;
  AssertThrow(added > 0, ExcBadInput(entry, "'" + file +
                                                "' adds no particle (none "
                                                "listed, or all cut by Holes)"));
  // Particles per cell direction: a cell's side over the particles' mean spacing.
  const double per_cell = added / spacing_sum;
  placement.particles_per_cell =
      static_cast<unsigned int>(std::clamp(std::round(per_cell), 1.0, 8.0));
  std::sort(fractions.begin(), fractions.end());
  recognise_rule(fractions, placement.particles_per_cell, placement);
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
  if (!body.particle_file.empty())
  {
    read_particle_file(body, b, grid, densities, thickness, store);
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
              if (!body.shape->inside(x) || !body.outside_holes(x))
                return;
              const unsigned int material = body.material_at(x);
              const double rho            = densities[material];
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
