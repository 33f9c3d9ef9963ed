#include <lme_mpm/base/input.h>
#include <lme_mpm/base/parameters.h>
#include <lme_mpm/scenes/scene_tools.h>

#include <cmath>
#include <sstream>

namespace lme_mpm
{
namespace scenes
{

/**
 * The Brazilian (splitting) test: a disc of diameter D pressed across its vertical
 * diameter by two bearing strips of width b that move towards each other. The scene
 * writes the bodies' shapes and the strips' prescribed velocities from its own
 * entries, so that the strip width or the loading rate is one number in the file:
 * the disc, and above and below it a strip whose inner face follows the disc's
 * surface over the width b (a curved jaw: the load spreads over the arc of
 * half-angle alpha, sin(alpha) = b/D, which the Hondros solution assumes).
 *
 * History: the crack opening across the loaded diameter (the change in distance
 * between two gauge points on the horizontal diameter). Summary: peak_force (the
 * largest contact force on the top strip, N, for the real thickness),
 * splitting_strength 2 P / (pi D t), the Hondros centre stress per unit load, and
 * where the damage lies (the share within D/10 of the loaded diameter).
 */
/// The Brazilian scene's entries, declared and read from this one list.
struct BrazilianEntries
{
  std::string centre, disc, top, bottom, disc_shape_text;
  double diameter = 0.15, length = 0.3, strip_width = 0.01, strip_thickness = 0.005;
  double velocity = 0.05, ramp = 1e-4, gauge = 0.075, stop_fraction = 0.3;
  double zone_depth          = 0;
  unsigned int zone_material = 2;

  void entries(EntryList &list)
  {
    list.add("Diameter", diameter, "0.15", Patterns::Double(),
             "The disc's diameter D (m), > 0.");
    list.add("Centre", centre, "0.1, 0.1", Patterns::Anything(),
             "The disc's centre (x, y in m; the axis runs along z in 3D).");
    list.add("Length", length, "0.3", Patterns::Double(),
             "3D only: the cylinder's length along z (m), from z = 0; > 0. In 2D the "
             "thickness is Problem/Thickness.");
    list.add("Strip width", strip_width, "0.010", Patterns::Double(),
             "Width b of the bearing strips (m), in (0, D).");
    list.add("Strip thickness", strip_thickness, "0.005", Patterns::Double(),
             "The strips' thickness at their middle (m), > 0.");
    list.add("Loading velocity", velocity, "0.05", Patterns::Double(),
             "The speed (m/s) at which each strip moves towards the centre, > 0; keep "
             "the loading time far above D / c_P.");
    list.add("Loading ramp time", ramp, "1e-4", Patterns::Double(),
             "The strips' speed rises smoothly from zero over this time (s), >= 0.");
    list.add("Opening gauge length", gauge, "0.075", Patterns::Double(),
             "The history column 'opening' is the change in distance between the "
             "disc's material points at x = cx -+ half this length on the horizontal "
             "diameter (m), in (0, D).");
    list.add("Stop at load fraction", stop_fraction, "0.3", Patterns::Double(),
             "Once the load (the top strip's force in a history row) has fallen below "
             "this fraction of its peak and some particle has begun to soften, the run "
             "ends, as a testing machine stops after the specimen fails; in [0, 1), 0: "
             "run to the end time.");
    list.add("Elastic zone depth", zone_depth, "0", Patterns::Double(),
             "The disc's particles within this depth (m) of a strip's contact arc, over "
             "the strip's width plus this depth on each side, are made of the elastic "
             "zone material (no fracture there: the concrete under a rigid jaw would "
             "otherwise fail in local crushing at the jaw's edges); >= 0, 0: none.");
    list.add("Elastic zone material", zone_material, "2", Patterns::Integer(1),
             "The number N of the 'Material N' of the elastic zones.");
    list.add("Disc", disc, "disc", Patterns::Anything(), "The Body N/Name of the disc.");
    list.add("Disc shape", disc_shape_text, "", Patterns::Anything(),
             "The disc body's Shape, if not the exact disc of Diameter about Centre: "
             "the same disc from a mesh or a polygon, e.g. 'mesh(disc.msh, 0.001)' "
             "(the strips, zones and gauges still follow Diameter and Centre). Empty: "
             "the exact disc; a disc body with a Particle file keeps its particles.");
    list.add("Top strip", top, "top", Patterns::Anything(),
             "The Body N/Name of the upper strip (its force is the load).");
    list.add("Bottom strip", bottom, "bottom", Patterns::Anything(),
             "The Body N/Name of the lower strip.");
  }
};

template <int dim>
class Brazilian : public Scene<dim>, private BrazilianEntries
{
public:
  /// The entries, declared by the registration.
  using Entries = BrazilianEntries;

  Brazilian(ParameterHandler &prm, const SceneContext<dim> &context)
      : BrazilianEntries(EntryList::parse<BrazilianEntries>(prm))
  {
    if (dim == 2)
      length = context.thickness;
    const Point<2> c = input::parse_point<2>(centre, entry("Centre"));
    cx = c[0], cy = c[1];
    input::require_positive({{diameter, entry("Diameter")},
                             {strip_thickness, entry("Strip thickness")},
                             {velocity, entry("Loading velocity")}});
    input::require_range(strip_width, 0, diameter, true, entry("Strip width"));
    input::require_range(ramp, 0, 1e300, false, entry("Loading ramp time"));
    input::require_range(gauge, 0, diameter, true, entry("Opening gauge length"));
    AssertThrow(gauge > 0 && gauge < diameter,
                ExcBadInput(entry("Opening gauge length"), "must lie in (0, D)"));
    input::require_range(zone_depth, 0, 0.5 * diameter, false,
                         entry("Elastic zone depth"));
    input::require_range(stop_fraction, 0, 1, false, entry("Stop at load fraction"));
    AssertThrow(stop_fraction < 1,
                ExcBadInput(entry("Stop at load fraction"), "must lie in [0, 1)"));
    if (dim == 3)
      AssertThrow(length > 0, ExcBadInput(entry("Length"), "must be positive"));
  }

  void write_entries(EntryWriter &writer) override
  {
    const double R = 0.5 * diameter, b = strip_width;
    const std::string disc_shape = cylinder_shape<dim>(cx, cy, R, length);
    // Height above the centre where the disc's surface meets x = cx -+ b/2.
    const double rise = std::sqrt(R * R - 0.25 * b * b);
    require_inside_grid(writer, cx - R, cy - R, cx + R, cy + R,
                        entry("Diameter") + "' and '" + entry("Centre"),
                        "the disc of diameter " + number(diameter) + " m about (" +
                            number(cx) + ", " + number(cy) + ")");
    add_opening_gauge(writer, gauge_name, Point<2>(cx - 0.5 * gauge, cy),
                      Point<2>(cx + 0.5 * gauge, cy), gauge_radius());
    // A disc from a particle file or from another shape (a mesh) replaces the exact
    // one; everything placed about it still follows Diameter and Centre.
    const std::string particle_file =
        writer.get(input::subsection_name("Body", writer.body(disc, entry("Disc"))) +
                   "/Particle file");
    AssertThrow(particle_file.empty() || input::trim(disc_shape_text).empty(),
                ExcBadInput(entry("Disc shape"),
                            "is set, and the disc body has a Particle file: give one"));
    if (particle_file.empty())
      writer.set_body(
          disc, "Shape",
          input::trim(disc_shape_text).empty() ? disc_shape : disc_shape_text,
          entry(input::trim(disc_shape_text).empty() ? "Disc" : "Disc shape"));
    if (zone_depth > 0)
    {
      const auto n_materials = std::stoul(writer.get("Problem/Number of materials"));
      AssertThrow(zone_material <= n_materials,
                  ExcBadInput(entry("Elastic zone material"),
                              "must be between 1 and Problem/Number of materials = " +
                                  std::to_string(n_materials)));
      // Under each strip: the cap of the disc beyond the strip's edge height less the
      // depth, over the strip's width plus the depth on each side.
      const double half   = 0.5 * b + zone_depth;
      const std::string m = std::to_string(zone_material) + ": ";
      writer.set_body(disc, "Material zones",
                      m +
                          box_shape<dim>(cx - half, cy + rise - zone_depth, cx + half,
                                         cy + R, length) +
                          "; " + m +
                          box_shape<dim>(cx - half, cy - R, cx + half,
                                         cy - rise + zone_depth, length),
                      entry("Elastic zone depth"));
    }
    // Each strip: a box from where the disc's surface meets x = cx -+ b/2 outwards,
    // minus the disc, so that its inner face follows the disc over the width b.
    for (const int side : {1, -1})
    {
      const std::string &name = side > 0 ? top : bottom;
      const std::string owner = entry(side > 0 ? "Top strip" : "Bottom strip");
      const double inner      = cy + side * rise;
      const double outer      = cy + side * (R + strip_thickness);
      const std::string shape =
          box_shape<dim>(cx - 0.5 * b, std::min(inner, outer), cx + 0.5 * b,
                         std::max(inner, outer), length);
      writer.set_body(name, "Shape", shape, owner);
      writer.set_body(name, "Holes", disc_shape, owner);
      // Towards the centre at the loading velocity after a cosine ramp.
      const std::string speed = ramp > 0
                                    ? "if(t < " + number(ramp) + ", " + number(velocity) +
                                          " * 0.5 * (1 - cos(pi * t / " + number(ramp) +
                                          ")), " + number(velocity) + ")"
                                    : number(velocity);
      std::string expression =
          "0; " + std::string(side > 0 ? "-" : "") + "(" + speed + ")";
      if (dim == 3)
        expression += "; 0";
      writer.set_body(name, "Prescribed velocity/Function expression", expression, owner);
    }
    fracture_energy = fracture_energy_of(writer, writer.body(disc, entry("Disc")));
  }

  void check(const SceneState<dim> &state) const override
  {
    (void)body_index(state, disc, entry("Disc"));
    (void)body_index(state, top, entry("Top strip"));
    (void)body_index(state, bottom, entry("Bottom strip"));
    AssertThrow(state.run->body_force.norm() == 0,
                ExcBadInput("Problem/Body force",
                            "the Brazilian test has no gravity (its "
                            "weight is negligible against the load)"));
    // Both gauge points must hold particles, or the opening would read zero.
    require_gauge_particles(state, gauge_name, entry("Opening gauge length"), "the disc");
  }

  void write_history_header(std::ostream &out) const override
  {
    out << ",opening,damage_centre,damage_total";
  }

  void write_history_row(std::ostream &out, const SceneState<dim> &state) const override
  {
    const unsigned int d = body_index(state, disc, entry("Disc"));
    out << "," << gauge_reading(state, gauge_name);
    // Where the crack starts: the damage-weighted volume of the disc within R/2 of
    // the centre, and in all of it.
    const ParticleStore<dim> &p = *state.particles;
    const double r2             = 0.0625 * diameter * diameter;
    double centre = 0, total = 0;
    for (std::size_t i = 0; i < p.size(); ++i)
      if (p.body_id[i] == d && p.damage[i] > 0)
      {
        const double w  = p.damage[i] * p.mass[i] / p.density[i];
        const double dx = p.reference_position[i][0] - cx,
                     dy = p.reference_position[i][1] - cy;
        total += w;
        if (dx * dx + dy * dy <= r2)
          centre += w;
      }
    out << "," << centre << "," << total;
  }

  std::string finished(const SceneState<dim> &state) const override
  {
    return load_fell_below(state, body_index(state, top, entry("Top strip")),
                           stop_fraction);
  }

  void add_results(const SceneState<dim> &state,
                   std::map<std::string, double> &results) const override
  {
    const auto force = results.find("peak_contact_force_" + top);
    if (force != results.end())
    {
      results["peak_force"]         = force->second;
      results["splitting_strength"] = 2 * force->second / (M_PI * diameter * length);
    }
    // Hondros: centre sigma_xx = (2 P / (pi D t)) (2 cos(alpha) - alpha / sin(alpha)).
    const double alpha               = std::asin(strip_width / diameter);
    results["hondros_centre_factor"] = 2 * std::cos(alpha) - alpha / std::sin(alpha);

    // Where the damage is: its volume-weighted share within D/10 of the loaded
    // diameter, and the vertical extent of the fully softened band there.
    const ParticleStore<dim> &p = *state.particles;
    const unsigned int d        = body_index(state, disc, entry("Disc"));
    double all = 0, near = 0, lo = 1e300, hi = -1e300;
    for (std::size_t i = 0; i < p.size(); ++i)
      if (p.body_id[i] == d && p.damage[i] > 0)
      {
        const double w = p.damage[i] * p.mass[i] / p.density[i];
        all += w;
        if (std::abs(p.reference_position[i][0] - cx) <= 0.1 * diameter)
        {
          near += w;
          if (p.damage[i] >= 0.99)
            lo = std::min(lo, p.reference_position[i][1]),
            hi = std::max(hi, p.reference_position[i][1]);
        }
      }
    results["damage_share_near_loaded_diameter"]  = all > 0 ? near / all : 0;
    results["softened_band_height_over_diameter"] = hi > lo ? (hi - lo) / diameter : 0;
    // The splitting crack: its band (of the particles with damage >= 0.5) and its area,
    // the length of the loaded diameter that has softened (damage > 0 within half a
    // band of it) times the thickness.
    const CrackPath path = crack_path(p, d, length, 0.5);
    const CrackBand band = crack_band(p, d, path, path.points);
    add_crack_band(band, results);
    const double half = 0.5 * std::max(band.width, path.spacing);
    double top = -1e300, bottom = 1e300;
    for (std::size_t i = 0; i < p.size(); ++i)
      if (p.body_id[i] == d && p.damage[i] > 0 &&
          std::abs(p.reference_position[i][0] - cx) <= half)
        top    = std::max(top, p.reference_position[i][1]),
        bottom = std::min(bottom, p.reference_position[i][1]);
    const double area     = top > bottom ? (top - bottom + path.spacing) * length : 0.0;
    results["crack_area"] = area;
    // Whether the split is one plane (the loaded diameter's) or branches and caps, in
    // units of the cell at the disc's centre (the mean of its sides).
    if (state.grid)
    {
      Point<dim> centre;
      centre[0] = cx, centre[1] = cy;
      if (dim == 3)
        centre[dim - 1] = 0.5 * length;
      std::array<unsigned int, dim> ijk;
      if (state.grid->locate(centre, ijk))
      {
        double cell = 0;
        for (unsigned int k = 0; k < dim; ++k)
          cell += state.grid->spacing(k, ijk[k]) / dim;
        results["crack_plane_deviation"] = crack_plane_deviation(p, d, cell);
      }
    }
    const auto dissipated = results.find("dissipated_energy");
    if (fracture_energy > 0 && area > 0 && dissipated != results.end())
      results["fracture_energy_ratio"] = dissipated->second / (fracture_energy * area);
  }

private:
  /// The opening gauge across the loaded diameter's normal: material points at
  /// (cx -+ gauge / 2, cy), the particles within 0.02 D of each (through the thickness).
  static constexpr const char *gauge_name = "diameter";
  double gauge_radius() const { return 0.02 * diameter; }

  static std::string entry(const std::string &name) { return "Scene/brazilian/" + name; }
  double cx = 0.1, cy = 0.1, fracture_energy = 0;
};
} // namespace scenes
} // namespace lme_mpm

using lme_mpm::scenes::Brazilian;
LME_MPM_REGISTER_SCENE(
    Brazilian, "brazilian",
    "the Brazilian splitting test: a disc (Diameter) between two bearing strips "
    "(Strip width) that close at the Loading velocity; writes the bodies' shapes and the "
    "strips' "
    "velocities, reports peak_force and splitting_strength.")
