#include <lme_mpm/base/input.h>
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
template <int dim>
class SemicircularBending : public Scene<dim>
{
public:
  static void declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Radius", "0.0475", Patterns::Double(),
                      "Semicircular bending: the specimen's radius R (m), > 0.");
    prm.declare_entry("Flat edge centre", "0.063, 0.015", Patterns::Anything(),
                      "Semicircular bending: the centre of the flat edge (x, y in m); "
                      "the arc lies above it.");
    prm.declare_entry("Length", "0.02", Patterns::Double(),
                      "Semicircular bending, 3D only: the specimen's length along z (m), "
                      "from z = 0. In 2D the thickness is Problem/Thickness.");
    prm.declare_entry("Notch angle", "0", Patterns::Double(),
                      "Semicircular bending: the notch's inclination from the vertical "
                      "(degrees), in [0, 90); positive towards -x.");
    prm.declare_entry("Notch length", "0.0166", Patterns::Double(),
                      "Semicircular bending: the notch's length (m), in (0, R).");
    prm.declare_entry("Notch width", "0.001", Patterns::Double(),
                      "Semicircular bending: the notch's width (m), > 0; at least the "
                      "particle spacing, or no particle is removed.");
    prm.declare_entry(
        "Notch crack", "true", Patterns::Bool(),
        "Semicircular bending, 2D: an explicit crack (Cracks) on the notch's centre "
        "line, from Scene/Notch crack overhang outside the flat edge to the notch tip, "
        "so that the grid does not tie the notch faces together where the notch is "
        "narrower than the shape functions' support. Not growing: the crack beyond the "
        "tip is the fracture model's. In 3D there are no explicit cracks and the entry "
        "must be false.");
    prm.declare_entry("Notch crack overhang", "0.008", Patterns::Double(),
                      "Semicircular bending: how far the notch crack reaches past the "
                      "flat edge along the notch's line (m); at least the shape "
                      "functions' support radius, so that no particle-node line passes "
                      "round the crack's mouth; > 0.");
    prm.declare_entry("Span", "0.0475", Patterns::Double(),
                      "Semicircular bending: the distance between the support rollers' "
                      "axes (m), in (0, 2R).");
    prm.declare_entry("Roller radius", "0.005", Patterns::Double(),
                      "Semicircular bending: the rollers' radius (m), > 0.");
    prm.declare_entry("Loading velocity", "0.002", Patterns::Double(),
                      "Semicircular bending: the loading roller's downward speed (m/s), "
                      "> 0.");
    prm.declare_entry("Loading ramp time", "1e-3", Patterns::Double(),
                      "Semicircular bending: the loading roller's speed rises smoothly "
                      "from zero over this time (s), >= 0.");
    prm.declare_entry(
        "Elastic zone depth", "0", Patterns::Double(),
        "Semicircular bending: the specimen's particles within this "
        "distance (m) of a roller's contact point are made of Scene/Elastic "
        "zone material (no fracture under the rollers); >= 0, 0: none.");
    prm.declare_entry("Elastic zone material", "2", Patterns::Integer(1),
                      "Semicircular bending: the number N of the 'Material N' of the "
                      "elastic zones.");
    prm.declare_entry("Stop at load fraction", "0.3", Patterns::Double(),
                      "Semicircular bending: once the load has fallen below this "
                      "fraction of its peak, the run ends; in [0, 1), 0: run to the end "
                      "time.");
    prm.declare_entry("Specimen", "specimen", Patterns::Anything(),
                      "Semicircular bending: the Body N/Name of the specimen.");
    prm.declare_entry("Loading roller", "load", Patterns::Anything(),
                      "Semicircular bending: the Body N/Name of the loading roller (its "
                      "force is the load).");
    prm.declare_entry("Support rollers", "left, right", Patterns::Anything(),
                      "Semicircular bending: the Body N/Name of the support rollers at "
                      "-x and +x.");
  }

  SemicircularBending(ParameterHandler &prm, const SceneContext<dim> &context)
      : n_bodies(context.n_bodies)
  {
    radius              = prm.get_double("Radius");
    length              = dim == 3 ? prm.get_double("Length") : context.thickness;
    angle               = prm.get_double("Notch angle");
    notch_length        = prm.get_double("Notch length");
    notch_width         = prm.get_double("Notch width");
    span                = prm.get_double("Span");
    roller              = prm.get_double("Roller radius");
    velocity            = prm.get_double("Loading velocity");
    ramp                = prm.get_double("Loading ramp time");
    notch_crack         = prm.get_bool("Notch crack");
    overhang            = prm.get_double("Notch crack overhang");
    zone_depth          = prm.get_double("Elastic zone depth");
    zone_material       = prm.get_integer("Elastic zone material");
    stop_fraction       = prm.get_double("Stop at load fraction");
    specimen            = input::trim(prm.get("Specimen"));
    load                = input::trim(prm.get("Loading roller"));
    const auto supports = input::split(prm.get("Support rollers"), ',');
    AssertThrow(supports.size() == 2,
                ExcBadInput("Scene/Support rollers", "needs two names, 'left, right'"));
    left  = input::trim(supports[0]);
    right = input::trim(supports[1]);
    const auto c =
        input::parse_doubles(prm.get("Flat edge centre"), "Scene/Flat edge centre");
    AssertThrow(c.size() == 2,
                ExcBadInput("Scene/Flat edge centre", "needs two numbers: x, y"));
    cx = c[0], cy = c[1];
    const double big = 1e300;
    input::require_range(radius, 0, big, true, "Scene/Radius");
    input::require_range(angle, 0, 90, false, "Scene/Notch angle");
    AssertThrow(angle < 90, ExcBadInput("Scene/Notch angle", "must lie in [0, 90)"));
    input::require_range(notch_length, 0, radius, true, "Scene/Notch length");
    input::require_range(notch_width, 0, radius, true, "Scene/Notch width");
    input::require_range(span, 0, 2 * radius, true, "Scene/Span");
    input::require_range(roller, 0, big, true, "Scene/Roller radius");
    input::require_range(velocity, 0, big, true, "Scene/Loading velocity");
    input::require_range(ramp, 0, big, false, "Scene/Loading ramp time");
    input::require_range(zone_depth, 0, radius, false, "Scene/Elastic zone depth");
    input::require_range(stop_fraction, 0, 1, false, "Scene/Stop at load fraction");
    AssertThrow(stop_fraction < 1,
                ExcBadInput("Scene/Stop at load fraction", "must lie in [0, 1)"));
    input::require_range(overhang, 0, big, true, "Scene/Notch crack overhang");
    if (dim == 3)
    {
      AssertThrow(length > 0, ExcBadInput("Scene/Length", "must be positive"));
      AssertThrow(!notch_crack,
                  ExcBadInput("Scene/Notch crack", "must be false in 3D (explicit "
                                                   "cracks exist in 2D only)"));
    }
  }

  void set_entries(ParameterHandler &prm) const override
  {
    const std::string rect_default =
        dim == 2 ? "rectangle(0, 0, 1, 1)" : "rectangle(0, 0, 0, 1, 1, 1)";
    // The half disc, curved side up (in 3D it fills the grid's z extent).
    const std::string half_disc =
        "half_disc(" + number(cx) + ", " + number(cy) + ", " + number(radius) + ", 90)";
    set_body_entry(prm, n_bodies, specimen, "Shape", half_disc, rect_default,
                   "Scene/Specimen");
    // The notch from the centre of the flat edge, up and towards -x by the angle.
    const std::string notch = "slot(" + number(cx) + ", " + number(cy) + ", " +
                              number(notch_length) + ", " + number(notch_width) + ", " +
                              number(90 + angle) + ")";
    set_body_entry(prm, n_bodies, specimen, "Holes", notch, "", "Scene/Notch angle");
    if (notch_crack)
    {
      const double a  = (90 + angle) * M_PI / 180;
      const double ux = std::cos(a), uy = std::sin(a);
      const std::string line =
          number(cx - overhang * ux) + ", " + number(cy - overhang * uy) + ", " +
          number(cx + notch_length * ux) + ", " + number(cy + notch_length * uy);
      set_notch_crack(prm, n_bodies, specimen, line, "Scene/Notch crack");
    }
    if (zone_depth > 0)
    {
      std::string zones;
      const std::string m = std::to_string(zone_material) + ": ";
      for (const auto &p : contact_points())
        zones += (zones.empty() ? "" : "; ") + m +
                 cylinder_shape<dim>(p[0], p[1], zone_depth, length);
      set_body_entry(prm, n_bodies, specimen, "Material zones", zones, "",
                     "Scene/Elastic zone depth");
    }
    // Rollers touching the flat edge from below and the top of the arc from above.
    const double gap = 0;
    for (const int side : {-1, 1})
    {
      const std::string &name = side < 0 ? left : right;
      set_body_entry(
          prm, n_bodies, name, "Shape",
          cylinder_shape<dim>(cx + 0.5 * side * span, cy - roller - gap, roller, length),
          rect_default, "Scene/Support rollers");
      set_body_entry(prm, n_bodies, name, "Prescribed velocity/Function expression",
                     ramped_velocity<dim>(0, 0, 0), "", "Scene/Support rollers");
    }
    set_body_entry(prm, n_bodies, load, "Shape",
                   cylinder_shape<dim>(cx, cy + radius + roller + gap, roller, length),
                   rect_default, "Scene/Loading roller");
    set_body_entry(prm, n_bodies, load, "Prescribed velocity/Function expression",
                   ramped_velocity<dim>(0, -velocity, ramp), "", "Scene/Loading roller");
  }

  void check(const SceneState<dim> &state) const override
  {
    (void)body_index(state, specimen, "Scene/Specimen");
    (void)body_index(state, load, "Scene/Loading roller");
    (void)body_index(state, left, "Scene/Support rollers");
    (void)body_index(state, right, "Scene/Support rollers");
  }

  void write_history_header(std::ostream &out) const override
  {
    out << ",opening,damage_total";
  }

  void write_history_row(std::ostream &out, const SceneState<dim> &state) const override
  {
    const unsigned int s        = body_index(state, specimen, "Scene/Specimen");
    const ParticleStore<dim> &p = *state.particles;
    // The notch mouth: material points on the flat edge 2.5 notch widths either side.
    const double g = 2.5 * notch_width, r = notch_width;
    const double opening = mean_displacement_near(p, s, Point<2>(cx + g, cy), r)[0] -
                           mean_displacement_near(p, s, Point<2>(cx - g, cy), r)[0];
    const double damaged = damaged_volume(p, s);
    out << "," << opening << "," << damaged;
  }

  std::string finished(const SceneState<dim> &state) const override
  {
    if (stop_fraction <= 0 || state.contact_forces == nullptr)
      return {};
    const unsigned int l = body_index(state, load, "Scene/Loading roller");
    const double peak    = (*state.peak_contact_forces)[l];
    if (peak > 0 && (*state.contact_forces)[l].norm() < stop_fraction * peak)
      return "the load fell below " + number(stop_fraction) + " of its peak";
    return {};
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
    const unsigned int s        = body_index(state, specimen, "Scene/Specimen");
    const double theta          = angle * M_PI / 180;
    const double tip_y          = cy + notch_length * std::cos(theta);
    double top                  = tip_y;
    for (std::size_t i = 0; i < p.size(); ++i)
      if (p.body_id[i] == s && p.damage[i] >= 0.99)
        top = std::max(top, p.reference_position[i][1]);
    results["softened_ligament_share"] = (top - tip_y) / (cy + radius - tip_y);
  }

private:
  /// Where the rollers touch the specimen: under the flat edge and at the top.
  std::vector<Point<2>> contact_points() const
  {
    return {Point<2>(cx - 0.5 * span, cy), Point<2>(cx + 0.5 * span, cy),
            Point<2>(cx, cy + radius)};
  }

  unsigned int n_bodies;
  double radius = 0.0475, length = 0.02, angle = 0, notch_length = 0.0166;
  double notch_width = 0.001, span = 0.0475, roller = 0.005, velocity = 0.002;
  double ramp = 1e-3, zone_depth = 0, stop_fraction = 0.3, cx = 0.063, cy = 0.015;
  bool notch_crack           = true;
  double overhang            = 0.008;
  unsigned int zone_material = 2;
  std::string specimen, load, left, right;
};
} // namespace scenes
} // namespace lme_mpm

using lme_mpm::scenes::SemicircularBending;
LME_MPM_REGISTER_SCENE(SemicircularBending, "semicircular bending",
                       "a notched half disc on two support rollers, loaded by a third "
                       "(Scene/Notch angle); writes the bodies' shapes and the rollers' "
                       "velocities, reports peak_force.")
