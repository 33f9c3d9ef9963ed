#include <lme_mpm/base/input.h>
#include <lme_mpm/base/parameters.h>
#include <lme_mpm/output/moving_mean.h>
#include <lme_mpm/scenes/scene_tools.h>

#include <cmath>

namespace lme_mpm
{
namespace scenes
{
/// The inclined tension bar's entries, declared and read from this one list.
struct InclinedTensionBarEntries
{
  std::string centre, bar, grips;
  double angle = 0, length = 0.4, width = 0.04, grip_length = 0.04;
  double weak_width = 0.005, velocity = 0.005, ramp = 1e-3;
  unsigned int weak_material = 2;

  void entries(EntryList &list)
  {
    list.add("Angle", angle, "0", Patterns::Double(),
             "The bar's axis against the grid's x axis (degrees), in [0, 90].");
    list.add("Centre", centre, "0.25, 0.25", Patterns::Anything(),
             "The middle of the bar (x, y in m).");
    list.add("Length", length, "0.4", Patterns::Double(),
             "The bar's length along its axis (m), grips included; > 2 grip lengths.");
    list.add("Width", width, "0.04", Patterns::Double(),
             "The bar's width W across its axis (m), > 0; in 2D the crack's area is W "
             "times Problem/Thickness.");
    list.add("Grip length", grip_length, "0.04", Patterns::Double(),
             "Each end's grip (m, along the axis, > 0): the grid nodes within the bar's "
             "width over this length are the constraint sets named in Grips, the one at "
             "the lower end held, the other pulled along the axis.");
    list.add("Weak zone width", weak_width, "0.005", Patterns::Double(),
             "A zone across the bar at mid-length this long along the axis (m) is made "
             "of the weak zone material, where the crack forms; 0: none.");
    list.add("Weak zone material", weak_material, "2", Patterns::Integer(1),
             "The number N of the 'Material N' of the weak zone; its Fracture/Fracture "
             "energy is the G_F the dissipated energy is compared with.");
    list.add("Loading velocity", velocity, "0.005", Patterns::Double(),
             "The speed (m/s) at which the upper grip moves along the axis, > 0.");
    list.add("Loading ramp time", ramp, "1e-3", Patterns::Double(),
             "The grip's speed rises smoothly from zero over this time (s), >= 0.");
    list.add("Bar", bar, "bar", Patterns::Anything(), "The Body N/Name of the bar.");
    list.add("Grips", grips, "held, pulled", Patterns::Anything(),
             "The Boundary conditions/Constraint N/Name of the held and of the pulled "
             "grip.");
  }
};

/**
 * A straight bar pulled apart along its own axis, which lies at an angle to the grid:
 * the crack band's energy for a crack that crosses the grid at that angle. The bar
 * (body Bar) is a rectangle of length L and width W centred on Centre; the grid nodes
 * in its grips (the last Grip length of each end, over the width) are two constraint
 * sets, the lower one held and the upper one moving along the axis at the loading
 * velocity after a cosine ramp (both velocity components prescribed). A weak zone
 * across the bar at mid-length (Weak zone material) makes the crack form there,
 * normal to the axis.
 *
 * History: axial_stress (the pulled grip's reaction along the axis over W t, as its
 * mean over the force window), axial_stress_mean (the same as the mean over the
 * row's interval) and extension (the grip's displacement along the axis). Summary:
 * peak_stress (the largest axial_stress over every step, N/m^2), crack_area (W t, m^2)
 * and fracture_energy_ratio, dissipated_energy / (G_F crack_area) with the weak zone's
 * G_F.
 */
template <int dim>
class InclinedTensionBar : public Scene<dim>, private InclinedTensionBarEntries
{
public:
  /// The entries, declared by the registration.
  using Entries = InclinedTensionBarEntries;

  InclinedTensionBar(ParameterHandler &prm, const SceneContext<dim> &context)
      : InclinedTensionBarEntries(EntryList::parse<InclinedTensionBarEntries>(prm)),
        thickness(context.thickness)
  {
    AssertThrow(dim == 2, ExcBadInput("Scene/Type", "the inclined tension bar is 2D"));
    const auto names = input::parse_names(grips, 2, entry("Grips"));
    held = names[0], pulled = names[1];
    const Point<2> c = input::parse_point<2>(centre, entry("Centre"));
    cx = c[0], cy = c[1];
    input::require_range(angle, 0, 90, false, entry("Angle"));
    input::require_positive({{width, entry("Width")},
                             {grip_length, entry("Grip length")},
                             {velocity, entry("Loading velocity")}});
    input::require_range(length, 2 * grip_length, 1e300, true, entry("Length"));
    input::require_range(weak_width, 0, length - 2 * grip_length, false,
                         entry("Weak zone width"));
    input::require_range(ramp, 0, 1e300, false, entry("Loading ramp time"));
    const double a = angle * M_PI / 180;
    ax = std::cos(a), ay = std::sin(a);
  }

  void write_entries(EntryWriter &writer) override
  {
    const std::string a = number(angle);
    // A slot from the point s along the axis from the bar's lower end, l long and
    // w wide.
    const auto along = [&](const double s, const double l, const double w)
    {
      const double x = cx + (s - 0.5 * length) * ax, y = cy + (s - 0.5 * length) * ay;
      return "slot(" + number(x) + ", " + number(y) + ", " + number(l) + ", " +
             number(w) + ", " + a + ")";
    };
    writer.set_body(bar, "Shape", along(0, length, width), entry("Bar"));
    if (weak_width > 0)
      writer.set_body(bar, "Material zones",
                      std::to_string(weak_material) + ": " +
                          along(0.5 * (length - weak_width), weak_width, 1.01 * width),
                      entry("Weak zone width"));
    for (const bool upper : {false, true})
    {
      const std::string section =
          "Boundary conditions/" +
          input::subsection_name(
              "Constraint", writer.constraint(upper ? pulled : held, entry("Grips")));
      writer.set(section + "/Shape",
                 along(upper ? length - grip_length : 0, grip_length, width),
                 entry("Grips"));
      writer.set(section + "/Components", "x, y", entry("Grips"));
      writer.set(section + "/Velocity/Function expression",
                 upper ? ramped_velocity<dim>(velocity * ax, velocity * ay, ramp)
                       : ramped_velocity<dim>(0, 0, 0),
                 entry("Grips"));
    }
    const std::string fracture =
        "Material " + std::to_string(weak_material) + "/Fracture/";
    fracture_energy = writer.get(fracture + "Model") == "none"
                          ? 0
                          : std::stod(writer.get(fracture + "Fracture energy"));
  }

  void check(const SceneState<dim> &state) const override
  {
    (void)body_index(state, bar, entry("Bar"));
    (void)constraint_named(state, held, entry("Grips"));
    (void)constraint_named(state, pulled, entry("Grips"));
  }

  void write_history_header(std::ostream &out) const override
  {
    out << ",axial_stress,axial_stress_mean,extension";
  }

  void write_history_row(std::ostream &out, const SceneState<dim> &state) const override
  {
    const NodeConstraint<dim> &grip = constraint_named(state, pulled, entry("Grips"));
    const double impulse            = grip.impulse()[0] * ax + grip.impulse()[1] * ay;
    const double interval           = state.time - last_time;
    // The pulled grip's reaction pulls the bar towards +axis: its mean over the row's
    // interval, beside the mean over the force window.
    const double mean =
        interval > 0 ? (impulse - last_impulse) / interval / (width * thickness) : 0.0;
    const double extension = grip.displacement()[0] * ax + grip.displacement()[1] * ay;
    last_time              = state.time;
    last_impulse           = impulse;
    out << "," << stress << "," << mean << "," << extension;
  }

  void observe(const SceneState<dim> &state) override
  {
    // The axial stress from the grip's reaction of this step, its mean over the force
    // window, and the largest that mean reaches.
    const NodeConstraint<dim> &grip = constraint_named(state, pulled, entry("Grips"));
    if (window.size() == 0)
      window.reset(1, state.force_window);
    const double step_stress =
        (grip.reaction()[0] * ax + grip.reaction()[1] * ay) / (width * thickness);
    window.book(&step_stress, state.step_length);
    stress      = window.mean(0);
    peak_stress = std::max(peak_stress, stress);
  }

  void add_results(const SceneState<dim> &,
                   std::map<std::string, double> &results) const override
  {
    const double area      = width * thickness;
    results["peak_stress"] = peak_stress;
    results["crack_area"]  = area;
    const auto dissipated  = results.find("dissipated_energy");
    if (dissipated != results.end() && fracture_energy > 0)
      results["fracture_energy_ratio"] = dissipated->second / (fracture_energy * area);
  }

  void serialize(Archive &ar) override
  {
    ar(last_time, last_impulse, stress, peak_stress);
    window.serialize(ar);
  }

private:
  static std::string entry(const std::string &name)
  {
    return "Scene/inclined tension bar/" + name;
  }

  double thickness;
  double cx = 0.25, cy = 0.25, ax = 1, ay = 0, fracture_energy = 0;
  std::string held, pulled;
  // What the last history row saw, and what observe() tracks after every step (kept
  // in checkpoints).
  mutable double last_time = 0, last_impulse = 0;
  MovingMean window;
  double stress = 0, peak_stress = 0;
};
} // namespace scenes
} // namespace lme_mpm

using lme_mpm::scenes::InclinedTensionBar;
LME_MPM_REGISTER_SCENE(InclinedTensionBar, "inclined tension bar",
                       "a bar pulled apart along its own axis at an Angle to the grid, "
                       "with a weak zone across it; reports peak_stress and the "
                       "dissipated energy per crack area against G_F.")
