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
  double angle = 0, out_of_plane_angle = 0, length = 0.4, width = 0.04,
         grip_length = 0.04;
  double weak_width = 0.005, velocity = 0.005, ramp = 1e-3;
  unsigned int weak_material = 2;

  void entries(EntryList &list)
  {
    list.add("Angle", angle, "0", Patterns::Double(),
             "The bar's axis against the grid's x axis (degrees), in [0, 90]; in 3D the "
             "turn about z.");
    list.add("Out-of-plane angle", out_of_plane_angle, "0", Patterns::Double(),
             "3D: the bar's axis, turned by Angle about z, is then tilted towards +z by "
             "this angle (degrees, in [0, 90]: a turn about the turned y axis), so that "
             "it points along (cos b cos a, cos b sin a, sin b); 0 in 2D.");
    list.add("Centre", centre, "0.25, 0.25", Patterns::Anything(),
             "The middle of the bar (x, y in m; x, y, z in 3D).");
    list.add("Length", length, "0.4", Patterns::Double(),
             "The bar's length along its axis (m), grips included; > 2 grip lengths.");
    list.add("Width", width, "0.04", Patterns::Double(),
             "The bar's width W across its axis (m), > 0; in 2D the crack's area is W "
             "times Problem/Thickness, in 3D the section is W x W.");
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
 * (body Bar) is a rectangle of length L and width W centred on Centre (in 3D a box of
 * section W x W, its axis turned by Angle about z and tilted by Out-of-plane angle
 * towards +z); the grid nodes in its grips (the last Grip length of each end, over the
 * section) are two constraint sets, the lower one held and the upper one moving along
 * the axis at the loading velocity after a cosine ramp (every velocity component
 * prescribed). A weak zone across the bar at mid-length (Weak zone material) makes the
 * crack form there, normal to the axis.
 *
 * History: axial_stress (the pulled grip's reaction along the axis over the section,
 * as its mean over the force window), axial_stress_mean (the same as the mean over the
 * row's interval) and extension (the grip's displacement along the axis). Summary:
 * peak_stress (the largest axial_stress over every step, N/m^2), crack_area (W t in
 * 2D, W^2 in 3D, m^2) and fracture_energy_ratio, dissipated_energy / (G_F crack_area)
 * with the weak zone's G_F.
 */
template <int dim>
class InclinedTensionBar : public Scene<dim>, private InclinedTensionBarEntries
{
public:
  /// The entries, declared by the registration.
  using Entries = InclinedTensionBarEntries;

  InclinedTensionBar(ParameterHandler &prm, const SceneContext<dim> &context)
      : InclinedTensionBarEntries(EntryList::parse<InclinedTensionBarEntries>(prm)),
        section_area(dim == 2 ? width * context.thickness : width * width)
  {
    const auto names = input::parse_names(grips, 2, entry("Grips"));
    held = names[0], pulled = names[1];
    middle = input::parse_point<dim>(centre, entry("Centre"));
    input::require_range(angle, 0, 90, false, entry("Angle"));
    input::require_range(out_of_plane_angle, 0, dim == 3 ? 90 : 0, false,
                         entry("Out-of-plane angle"));
    input::require_positive({{width, entry("Width")},
                             {grip_length, entry("Grip length")},
                             {velocity, entry("Loading velocity")}});
    input::require_range(length, 2 * grip_length, 1e300, true, entry("Length"));
    input::require_range(weak_width, 0, length - 2 * grip_length, false,
                         entry("Weak zone width"));
    input::require_range(ramp, 0, 1e300, false, entry("Loading ramp time"));
    const double a = angle * M_PI / 180, b = out_of_plane_angle * M_PI / 180;
    axis[0] = std::cos(b) * std::cos(a), axis[1] = std::cos(b) * std::sin(a);
    if (dim == 3)
      axis[dim - 1] = std::sin(b);
  }

  void write_entries(EntryWriter &writer) override
  {
    // A piece of the bar from the point s along the axis from its lower end, l long
    // and w wide (and deep in 3D).
    const auto along = [&](const double s, const double l, const double w)
    {
      if (dim == 2)
      {
        const Point<dim> start = middle + (s - 0.5 * length) * axis;
        return "slot(" + number(start[0]) + ", " + number(start[1]) + ", " + number(l) +
               ", " + number(w) + ", " + number(angle) + ")";
      }
      const Point<dim> mid = middle + (s + 0.5 * l - 0.5 * length) * axis;
      std::string text     = "turned_box(";
      for (unsigned int d = 0; d < dim; ++d)
        text += number(mid[d]) + ", ";
      return text + number(l) + ", " + number(w) + ", " + number(w) + ", " +
             number(angle) + ", " + number(out_of_plane_angle) + ")";
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
      writer.set(section + "/Components", dim == 2 ? "x, y" : "x, y, z", entry("Grips"));
      writer.set(section + "/Velocity/Function expression",
                 ramped_velocity<dim>(upper ? velocity * axis : Tensor<1, dim>(),
                                      upper ? ramp : 0),
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
    const double impulse            = grip.impulse() * axis;
    const double interval           = state.time - last_time;
    // The pulled grip's reaction pulls the bar towards +axis: its mean over the row's
    // interval, beside the mean over the force window.
    const double mean =
        interval > 0 ? (impulse - last_impulse) / interval / section_area : 0.0;
    const double extension = grip.displacement() * axis;
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
    const double step_stress = grip.reaction() * axis / section_area;
    window.book(&step_stress, state.step_length);
    stress      = window.mean(0);
    peak_stress = std::max(peak_stress, stress);
  }

  void add_results(const SceneState<dim> &,
                   std::map<std::string, double> &results) const override
  {
    results["peak_stress"] = peak_stress;
    results["crack_area"]  = section_area;
    const auto dissipated  = results.find("dissipated_energy");
    if (dissipated != results.end() && fracture_energy > 0)
      results["fracture_energy_ratio"] =
          dissipated->second / (fracture_energy * section_area);
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

  double section_area;
  Point<dim> middle;
  Tensor<1, dim> axis;
  double fracture_energy = 0;
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
