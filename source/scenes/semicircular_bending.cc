#include <lme_mpm/base/input.h>
#include <lme_mpm/base/parameters.h>
#include <lme_mpm/scenes/scene_tools.h>

#include <cmath>

namespace lme_mpm
{
namespace scenes
{
/**
 * Semicircular bending (SCB): a half disc of radius R, flat edge down, on two support
 * rollers at span S symmetric about the centre of the flat edge, pressed at the top of
 * its arc by a loading roller that moves down at the loading velocity after a cosine
 * ramp. A notch of given length and width runs from the centre of the flat edge,
 * inclined by the notch angle from the vertical. The scene writes the specimen's shape
 * and notch, the rollers' shapes and velocities (and optional elastic zones at the
 * three contacts) from its own entries.
 *
 * History: the notch-mouth opening and the damaged volume. Summary: peak_force (the
 * loading roller's largest contact force, N, for the real thickness) and how far up
 * the fully softened particles reach.
 */
/// The semicircular-bending scene's entries, declared and read from this one list.
struct SemicircularBendingEntries
{
  double radius = 0.0475, length = 0.02, angle = 0, notch_length = 0.0166;
  double notch_width = 0.001, span = 0.0475, roller = 0.005, velocity = 0.002;
  double ramp = 1e-3, zone_depth = 0, stop_fraction = 0.3, overhang = 0.008;
  bool notch_crack           = true;
  unsigned int zone_material = 2;
  std::string centre, specimen, load, supports;

  void entries(EntryList &list)
  {
    list.add("Radius", radius, "0.0475", Patterns::Double(),
             "The specimen's radius R (m), > 0.");
    list.add("Flat edge centre", centre, "0.063, 0.015", Patterns::Anything(),
             "The centre of the flat edge (x, y in m); the arc lies above it.");
    list.add("Notch angle", angle, "0", Patterns::Double(),
             "The notch's inclination from the vertical (degrees), in [0, 90); "
             "positive towards -x.");
    list.add("Length", length, "0.02", Patterns::Double(),
             "3D only: the specimen's length along z (m), from z = 0. In 2D the "
             "thickness is Problem/Thickness.");
    list.add("Notch length", notch_length, "0.0166", Patterns::Double(),
             "The notch's length (m), in (0, R).");
    list.add("Notch width", notch_width, "0.001", Patterns::Double(),
             "The notch's width (m), > 0; at least the particle spacing, or no particle "
             "is removed.");
    list.add("Notch crack", notch_crack, "true", Patterns::Bool(),
             "2D: an explicit crack (Cracks) on the notch's centre line, from the notch "
             "crack overhang outside the flat edge to the notch tip, so that the grid "
             "does not tie the notch faces together where the notch is narrower than "
             "the shape functions' support. Not growing: the crack beyond the tip is "
             "the fracture model's. In 3D there are no explicit cracks and the entry "
             "must be false.");
    list.add("Notch crack overhang", overhang, "0.008", Patterns::Double(),
             "How far the notch crack reaches past the flat edge along the notch's line "
             "(m); at least the shape functions' support radius, so that no "
             "particle-node line passes round the crack's mouth; > 0.");
    list.add("Span", span, "0.0475", Patterns::Double(),
             "The distance between the support rollers' axes (m), in (0, 2R).");
    list.add("Roller radius", roller, "0.005", Patterns::Double(),
             "The rollers' radius (m), > 0.");
    list.add("Loading velocity", velocity, "0.002", Patterns::Double(),
             "The loading roller's downward speed (m/s), > 0.");
    list.add("Loading ramp time", ramp, "1e-3", Patterns::Double(),
             "The loading roller's speed rises smoothly from zero over this time (s), "
             ">= 0.");
    list.add("Elastic zone depth", zone_depth, "0", Patterns::Double(),
             "The specimen's particles within this distance (m) of a roller's contact "
             "point are made of the elastic zone material (no fracture under the "
             "rollers); >= 0, 0: none.");
    list.add("Elastic zone material", zone_material, "2", Patterns::Integer(1),
             "The number N of the 'Material N' of the elastic zones.");
    list.add("Stop at load fraction", stop_fraction, "0.3", Patterns::Double(),
             "Once the load has fallen below this fraction of its peak and some particle "
             "has begun to soften, the run ends; in [0, 1), 0: run to the end time.");
    list.add("Specimen", specimen, "specimen", Patterns::Anything(),
             "The Body N/Name of the specimen.");
    list.add("Loading roller", load, "load", Patterns::Anything(),
             "The Body N/Name of the loading roller (its force is the load).");
    list.add("Support rollers", supports, "left, right", Patterns::Anything(),
             "The Body N/Name of the support rollers at -x and +x.");
  }
};

template <int dim>
class SemicircularBending : public Scene<dim>, private SemicircularBendingEntries
{
public:
  using Entries = SemicircularBendingEntries; ///< declared by the registration

  SemicircularBending(ParameterHandler &prm, const SceneContext<dim> &context)
      : SemicircularBendingEntries(EntryList::parse<SemicircularBendingEntries>(prm))
  {
    const auto rollers = input::parse_names(supports, 2, entry("Support rollers"));
    left = rollers[0], right = rollers[1];
    const Point<2> c = input::parse_point<2>(centre, entry("Flat edge centre"));
    cx = c[0], cy = c[1];
    // In 2D the specimen is as long as the run's thickness.
    if (dim == 2)
      length = context.thickness;
    input::require_positive({{radius, entry("Radius")},
                             {roller, entry("Roller radius")},
                             {velocity, entry("Loading velocity")},
                             {overhang, entry("Notch crack overhang")}});
    input::require_range(angle, 0, 90, false, entry("Notch angle"));
    AssertThrow(angle < 90, ExcBadInput(entry("Notch angle"), "must lie in [0, 90)"));
    input::require_range(notch_length, 0, radius, true, entry("Notch length"));
    input::require_range(notch_width, 0, radius, true, entry("Notch width"));
    input::require_range(span, 0, 2 * radius, true, entry("Span"));
    input::require_range(ramp, 0, 1e300, false, entry("Loading ramp time"));
    input::require_range(zone_depth, 0, radius, false, entry("Elastic zone depth"));
    input::require_range(stop_fraction, 0, 1, false, entry("Stop at load fraction"));
    AssertThrow(stop_fraction < 1,
                ExcBadInput(entry("Stop at load fraction"), "must lie in [0, 1)"));
    if (dim == 3)
    {
      AssertThrow(length > 0, ExcBadInput(entry("Length"), "must be positive"));
      AssertThrow(!notch_crack,
                  ExcBadInput(entry("Notch crack"), "must be false in 3D (explicit "
                                                    "cracks exist in 2D only)"));
    }
  }

  void write_entries(EntryWriter &writer) override
  {
    // The notch mouth's gauge: material points on the flat edge 2.5 notch widths
    // either side of the notch, the particles within a notch width of each.
    add_opening_gauge(writer, gauge_name, Point<2>(cx - 2.5 * notch_width, cy),
                      Point<2>(cx + 2.5 * notch_width, cy), notch_width);
    // The half disc, curved side up (in 3D it fills the grid's z extent).
    const std::string half_disc =
        "half_disc(" + number(cx) + ", " + number(cy) + ", " + number(radius) + ", 90)";
    require_inside_grid(writer, cx - radius, cy, cx + radius, cy + radius,
                        entry("Radius") + "' and '" + entry("Flat edge centre"),
                        "the half disc of radius " + number(radius) + " m from (" +
                            number(cx) + ", " + number(cy) + ")");
    writer.set_body(specimen, "Shape", half_disc, entry("Specimen"));
    // The notch from the centre of the flat edge, up and towards -x by the angle.
    const std::string notch = "slot(" + number(cx) + ", " + number(cy) + ", " +
                              number(notch_length) + ", " + number(notch_width) + ", " +
                              number(90 + angle) + ")";
    writer.set_body(specimen, "Holes", notch, entry("Notch angle"));
    if (notch_crack)
    {
      const double a  = (90 + angle) * M_PI / 180;
      const double ux = std::cos(a), uy = std::sin(a);
      const std::string line =
          number(cx - overhang * ux) + ", " + number(cy - overhang * uy) + ", " +
          number(cx + notch_length * ux) + ", " + number(cy + notch_length * uy);
      set_notch_crack(writer, specimen, line, entry("Notch crack"));
    }
    if (zone_depth > 0)
    {
      std::string zones;
      const std::string m = std::to_string(zone_material) + ": ";
      for (const auto &p : contact_points())
        zones += (zones.empty() ? "" : "; ") + m +
                 cylinder_shape<dim>(p[0], p[1], zone_depth, length);
      writer.set_body(specimen, "Material zones", zones, entry("Elastic zone depth"));
    }
    // Rollers touching the flat edge from below and the top of the arc from above.
    for (const int side : {-1, 1})
    {
      const std::string &name = side < 0 ? left : right;
      writer.set_body(
          name, "Shape",
          cylinder_shape<dim>(cx + 0.5 * side * span, cy - roller, roller, length),
          entry("Support rollers"));
      writer.set_body(name, "Prescribed velocity/Function expression",
                      ramped_velocity<dim>(0, 0, 0), entry("Support rollers"));
    }
    writer.set_body(load, "Shape",
                    cylinder_shape<dim>(cx, cy + radius + roller, roller, length),
                    entry("Loading roller"));
    writer.set_body(load, "Prescribed velocity/Function expression",
                    ramped_velocity<dim>(0, -velocity, ramp), entry("Loading roller"));
    fracture_energy =
        fracture_energy_of(writer, writer.body(specimen, entry("Specimen")));
  }

  void check(const SceneState<dim> &state) const override
  {
    (void)body_index(state, specimen, entry("Specimen"));
    (void)body_index(state, load, entry("Loading roller"));
    (void)body_index(state, left, entry("Support rollers"));
    (void)body_index(state, right, entry("Support rollers"));
  }

  void write_history_header(std::ostream &out) const override
  {
    out << ",opening,damage_total";
  }

  void write_history_row(std::ostream &out, const SceneState<dim> &state) const override
  {
    const unsigned int s        = body_index(state, specimen, entry("Specimen"));
    const ParticleStore<dim> &p = *state.particles;
    out << "," << gauge_reading(state, gauge_name) << "," << damaged_volume(p, s);
  }

  std::string finished(const SceneState<dim> &state) const override
  {
    return load_fell_below(state, body_index(state, load, entry("Loading roller")),
                           stop_fraction);
  }

  void add_results(const SceneState<dim> &state,
                   std::map<std::string, double> &results) const override
  {
    const auto force = results.find("peak_contact_force_" + load);
    if (force != results.end())
      results["peak_force"] = force->second;
    // How far the crack got: the highest fully softened particle above the notch
    // tip, as a share of the ligament from the tip to the top of the arc.
    const ParticleStore<dim> &p = *state.particles;
    const unsigned int s        = body_index(state, specimen, entry("Specimen"));
    const double theta          = angle * M_PI / 180;
    const double tip_y          = cy + notch_length * std::cos(theta);
    double top                  = tip_y;
    for (std::size_t i = 0; i < p.size(); ++i)
      if (p.body_id[i] == s && p.damage[i] >= 0.99)
        top = std::max(top, p.reference_position[i][1]);
    results["softened_ligament_share"] = (top - tip_y) / (cy + radius - tip_y);
    add_crack_energy(p, s, length, fracture_energy, results);
    // The crack from the notch tip: its band (damage >= 0.5) and what it dissipated.
    const Point<2> tip(cx - notch_length * std::sin(theta), tip_y);
    const CrackPath path = crack_path(p, s, length, 0.5, &tip);
    add_crack_band(crack_band(p, s, path, path.points), results);
  }

private:
  /// Where the rollers touch the specimen: under the flat edge and at the top.
  std::vector<Point<2>> contact_points() const
  {
    return {Point<2>(cx - 0.5 * span, cy), Point<2>(cx + 0.5 * span, cy),
            Point<2>(cx, cy + radius)};
  }

  static std::string entry(const std::string &name)
  {
    return "Scene/semicircular bending/" + name;
  }
  double cx = 0.063, cy = 0.015, fracture_energy = 0;
  static constexpr const char *gauge_name = "notch_mouth";
  std::string left, right;
};
} // namespace scenes
} // namespace lme_mpm

using lme_mpm::scenes::SemicircularBending;
LME_MPM_REGISTER_SCENE(SemicircularBending, "semicircular bending",
                       "a notched half disc on two support rollers, loaded by a third "
                       "(Notch angle); writes the bodies' shapes and the rollers' "
                       "velocities, reports peak_force.")
