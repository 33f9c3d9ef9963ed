#include <lme_mpm/base/input.h>
#include <lme_mpm/base/parameters.h>
#include <lme_mpm/scenes/scene_tools.h>

#include <algorithm>
#include <cmath>

namespace lme_mpm
{
namespace scenes
{
/// The three-point-bending scene's entries, declared and read from this one list.
struct ThreePointBendingEntries
{
  double length = 0.175, depth = 0.05, width = 0.05, span = 0.125;
  double notch_depth = 0.025, notch_width = 0.0025, roller = 0.005;
  double velocity = 0.02, ramp = 5e-4, cmod_rate = 0.02, gauge_length = 0.01;
  double gauge_radius = 0, overhang = 0.008, stop_fraction = 0.05;
  bool notch_crack = true;
  std::string corner, control, specimen, load, supports;

  void entries(EntryList &list)
  {
    list.add("Beam corner", corner, "0.01, 0.01", Patterns::Anything(),
             "The beam's lower-left corner (x, y in m); the beam lies along x, its "
             "bottom face at y.");
    list.add("Length", length, "0.175", Patterns::Double(),
             "The beam's length L along x (m), > 0.");
    list.add("Depth", depth, "0.05", Patterns::Double(),
             "The beam's depth D along y (m), > 0.");
    list.add("Width", width, "0.05", Patterns::Double(),
             "3D only: the beam's width b along z (m), from z = 0. In 2D the width is "
             "Problem/Thickness.");
    list.add("Span", span, "0.125", Patterns::Double(),
             "The distance S between the support rollers' axes (m), in (0, L), centred "
             "on the beam.");
    list.add("Notch depth", notch_depth, "0.025", Patterns::Double(),
             "The notch's depth a0 from the bottom face at mid-length (m), in (0, D).");
    list.add("Notch width", notch_width, "0.0025", Patterns::Double(),
             "The notch's width (m), > 0; at least the particle spacing, or no particle "
             "is removed.");
    list.add("Notch crack", notch_crack, "true", Patterns::Bool(),
             "2D: an explicit crack (Cracks) on the notch's centre line, from the notch "
             "crack overhang below the bottom face to the notch tip, so that the grid "
             "does not tie the notch faces together where the notch is narrower than "
             "the shape functions' support. In 3D there are no explicit cracks and the "
             "entry must be false.");
    list.add("Notch crack overhang", overhang, "0.008", Patterns::Double(),
             "How far the notch crack reaches below the bottom face (m); at least the "
             "shape functions' support radius; > 0.");
    list.add("Roller radius", roller, "0.005", Patterns::Double(),
             "The radius of the loading and support rollers (m), > 0.");
    list.add("Control", control, "CMOD", Patterns::Selection("CMOD|deflection"),
             "How the loading roller is driven. 'CMOD': a servo (Loading control) "
             "moves it so that the crack mouth opening grows at the CMOD rate, the "
             "loading velocity being the press's fastest stroke; 'deflection': it moves "
             "down at the loading velocity.");
    list.add("Loading velocity", velocity, "0.02", Patterns::Double(),
             "The loading roller's downward speed (m/s), > 0: the deflection rate, or "
             "under CMOD control the fastest stroke.");
    list.add("Loading ramp time", ramp, "5e-4", Patterns::Double(),
             "The loading roller's speed rises smoothly from zero over this time (s), "
             ">= 0.");
    list.add("CMOD rate", cmod_rate, "0.02", Patterns::Double(),
             "Under CMOD control: the rate the crack mouth opening is held to (m/s), > "
             "0.");
    list.add("CMOD gauge length", gauge_length, "0.01", Patterns::Double(),
             "The distance between the clip gauge's two points on the bottom face, "
             "centred on the notch (m); larger than the notch width plus two gauge "
             "radii.");
    list.add("CMOD gauge radius", gauge_radius, "0", Patterns::Double(),
             "Each gauge point averages the particles within this distance (m); 0: "
             "half the gap between the notch face and the point, at most the notch "
             "width; >= 0.");
    list.add("Stop at load fraction", stop_fraction, "0.05", Patterns::Double(),
             "Once the load has fallen below this fraction of its peak and some particle "
             "has begun to soften, the run ends; in [0, 1), 0: run to the end time.");
    list.add("Specimen", specimen, "beam", Patterns::Anything(),
             "The Body N/Name of the beam.");
    list.add("Loading roller", load, "load", Patterns::Anything(),
             "The Body N/Name of the loading roller (its force is the load).");
    list.add("Support rollers", supports, "left, right", Patterns::Anything(),
             "The Body N/Name of the support rollers at -x and +x.");
  }
};

/**
 * A notched beam in three-point bending (RILEM TC-50): a beam of length L and depth D
 * on two support rollers at span S, with a notch of depth a0 from the bottom face at
 * mid-length, loaded by a third roller on the top face above the notch. The load is
 * driven at a constant deflection rate, or (the default, as a laboratory runs the
 * test) by a servo that holds the crack mouth opening's rate (Loading control). The
 * clip gauge across the notch mouth is the opening gauge `cmod`.
 *
 * Rigid exact rollers (Body N/Surface = exact) are seated: the scene sets Contact/Seat
 * rigid surfaces, so that the loading roller comes down onto the beam and the supports,
 * written a fifth of a cell into the beam, back off until they touch its particles.
 *
 * History: the gauge's opening_cmod, the loading roller's force_load_... and
 * displacement_load_... (the load-point deflection from its seat), and the damaged
 * volume. Summary: peak_force, the RILEM work of fracture against the ligament
 * area, and the crack band's width and path.
 */
template <int dim>
class ThreePointBending : public Scene<dim>, private ThreePointBendingEntries
{
public:
  using Entries = ThreePointBendingEntries; ///< declared by the registration

  ThreePointBending(ParameterHandler &prm, const SceneContext<dim> &context)
      : ThreePointBendingEntries(EntryList::parse<ThreePointBendingEntries>(prm))
  {
    const auto rollers = input::parse_names(supports, 2, entry("Support rollers"));
    left = rollers[0], right = rollers[1];
    const Point<2> c = input::parse_point<2>(corner, entry("Beam corner"));
    x0 = c[0], y0 = c[1];
    if (dim == 2)
      width = context.thickness;
    input::require_positive({{length, entry("Length")},
                             {depth, entry("Depth")},
                             {roller, entry("Roller radius")},
                             {velocity, entry("Loading velocity")},
                             {cmod_rate, entry("CMOD rate")},
                             {overhang, entry("Notch crack overhang")}});
    input::require_range(span, 0, length, true, entry("Span"));
    input::require_range(notch_depth, 0, depth, true, entry("Notch depth"));
    input::require_range(notch_width, 0, 0.5 * span, true, entry("Notch width"));
    input::require_range(ramp, 0, 1e300, false, entry("Loading ramp time"));
    input::require_range(gauge_radius, 0, 1e300, false, entry("CMOD gauge radius"));
    input::require_range(stop_fraction, 0, 1, false, entry("Stop at load fraction"));
    AssertThrow(stop_fraction < 1,
                ExcBadInput(entry("Stop at load fraction"), "must lie in [0, 1)"));
    if (gauge_radius == 0)
      gauge_radius = std::min(0.25 * (gauge_length - notch_width), notch_width);
    AssertThrow(gauge_length > notch_width + 2 * gauge_radius,
                ExcBadInput(entry("CMOD gauge length"),
                            "is " + number(gauge_length) +
                                " m: it must exceed the notch width (" +
                                number(notch_width) + " m) plus two gauge radii (" +
                                number(gauge_radius) +
                                " m each), so that each point lies on one side"));
    AssertThrow(gauge_length < span,
                ExcBadInput(entry("CMOD gauge length"),
                            "is " + number(gauge_length) +
                                " m: it must be shorter than the span (" + number(span) +
                                " m)"));
    if (dim == 3)
    {
      AssertThrow(width > 0, ExcBadInput(entry("Width"), "must be positive"));
      AssertThrow(!notch_crack,
                  ExcBadInput(entry("Notch crack"), "must be false in 3D (explicit "
                                                    "cracks exist in 2D only)"));
    }
  }

  void write_entries(EntryWriter &writer) override
  {
    const double xm = x0 + 0.5 * length;
    require_inside_grid(writer, x0, y0 - 2 * roller, x0 + length, y0 + depth + 2 * roller,
                        entry("Beam corner") + "', '" + entry("Length") + "', '" +
                            entry("Depth") + "' and '" + entry("Roller radius"),
                        "the beam with its rollers");
    writer.set_body(specimen, "Shape",
                    box_shape<dim>(x0, y0, x0 + length, y0 + depth, width),
                    entry("Specimen"));
    writer.set_body(specimen, "Holes",
                    box_shape<dim>(xm - 0.5 * notch_width, y0 - 0.5 * notch_width,
                                   xm + 0.5 * notch_width, y0 + notch_depth, width),
                    entry("Notch depth"));
    if (notch_crack)
      set_notch_crack(writer, specimen,
                      number(xm) + ", " + number(y0 - overhang) + ", " + number(xm) +
                          ", " + number(y0 + notch_depth),
                      entry("Notch crack"));
    add_opening_gauge(writer, gauge_name, Point<2>(xm - 0.5 * gauge_length, y0),
                      Point<2>(xm + 0.5 * gauge_length, y0), gauge_radius);

    // Exact rollers are seated; the supports, which do not move, are written a fifth
    // of a cell into the beam so that seating backs them off onto its particles
    // (a support whose top falls between two particles would otherwise stand off
    // their domains, and the beam would first drop onto it).
    const auto is_exact = [&](const std::string &name, const std::string &owner)
    {
      const unsigned int n = writer.body(name, owner) + 1;
      return writer.get("Body " + std::to_string(n) + "/Surface") == "exact";
    };
    double lift = 0;
    if (is_exact(load, entry("Loading roller")) ||
        is_exact(left, entry("Support rollers")) ||
        is_exact(right, entry("Support rollers")))
    {
      writer.set("Contact/Seat rigid surfaces", "true", entry("Loading roller"),
                 "(rigid exact rollers are seated on the beam)");
      const auto h = input::parse_doubles(writer.get("Grid/Cell size"), "Grid/Cell size");
      lift         = h.empty() ? 0 : 0.2 * *std::min_element(h.begin(), h.end());
    }
    for (const int side : {-1, 1})
    {
      const std::string &name = side < 0 ? left : right;
      writer.set_body(
          name, "Shape",
          cylinder_shape<dim>(xm + 0.5 * side * span, y0 - roller + lift, roller, width),
          entry("Support rollers"));
      writer.set_body(name, "Prescribed velocity/Function expression",
                      ramped_velocity<dim>(0, 0, 0), entry("Support rollers"));
    }
    writer.set_body(load, "Shape",
                    cylinder_shape<dim>(xm, y0 + depth + roller, roller, width),
                    entry("Loading roller"));
    writer.set_body(load, "Prescribed velocity/Function expression",
                    ramped_velocity<dim>(0, -velocity, ramp), entry("Loading roller"));
    if (control == "CMOD")
    {
      writer.set("Loading control/Type", "opening rate", entry("Control"));
      writer.set("Loading control/Gauge", gauge_name, entry("Control"));
      writer.set("Loading control/Devices", load, entry("Control"));
      writer.set("Loading control/Opening rate", number(cmod_rate), entry("CMOD rate"));
    }
    fracture_energy =
        fracture_energy_of(writer, writer.body(specimen, entry("Specimen")));
  }

  void check(const SceneState<dim> &state) const override
  {
    (void)body_index(state, specimen, entry("Specimen"));
    (void)body_index(state, load, entry("Loading roller"));
    (void)body_index(state, left, entry("Support rollers"));
    (void)body_index(state, right, entry("Support rollers"));
    require_gauge_particles(state, gauge_name, entry("CMOD gauge length"),
                            "the clip gauge across the notch mouth");
  }

  void write_history_header(std::ostream &out) const override { out << ",damage_total"; }

  void write_history_row(std::ostream &out, const SceneState<dim> &state) const override
  {
    const unsigned int s = body_index(state, specimen, entry("Specimen"));
    out << "," << damaged_volume(*state.particles, s);
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
    const ParticleStore<dim> &p = *state.particles;
    const unsigned int s        = body_index(state, specimen, entry("Specimen"));
    // RILEM TC-50: the work of fracture over the ligament's area.
    const double ligament    = (depth - notch_depth) * width;
    results["ligament_area"] = ligament;
    const auto work          = results.find("work_of_fracture");
    if (work != results.end() && fracture_energy > 0)
      results["rilem_fracture_energy_ratio"] = work->second / ligament / fracture_energy;
    // How far the crack got: the highest fully softened particle above the notch
    // tip, as a share of the ligament.
    const double xm = x0 + 0.5 * length, tip_y = y0 + notch_depth;
    double top = tip_y;
    for (std::size_t i = 0; i < p.size(); ++i)
      if (p.body_id[i] == s && p.damage[i] >= 0.99)
        top = std::max(top, p.reference_position[i][1]);
    results["softened_ligament_share"] = (top - tip_y) / (depth - notch_depth);
    add_crack_energy(p, s, width, fracture_energy, results);
    const Point<2> tip(xm, tip_y);
    const CrackPath path = crack_path(p, s, width, 0.5, &tip);
    add_crack_band(crack_band(p, s, path, path.points), results);
    // The path's largest distance from the notch's line, in m (a straight crack: 0).
    double deviation = 0;
    for (const auto &q : path.points)
      deviation = std::max(deviation, std::abs(q[0] - xm));
    results["crack_path_max_offset"] = deviation;
  }

private:
  static std::string entry(const std::string &name)
  {
    return "Scene/three point bending/" + name;
  }
  double x0 = 0.01, y0 = 0.01, fracture_energy = 0;
  static constexpr const char *gauge_name = "cmod";
  std::string left, right;
};
} // namespace scenes
} // namespace lme_mpm

using lme_mpm::scenes::ThreePointBending;
LME_MPM_REGISTER_SCENE(ThreePointBending, "three point bending",
                       "a notched beam on two support rollers loaded by a third above "
                       "the notch (RILEM TC-50), under CMOD control or at a constant "
                       "deflection rate; reports peak_force and the work of fracture.")
