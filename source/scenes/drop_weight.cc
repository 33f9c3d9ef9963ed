#include <lme_mpm/base/input.h>
#include <lme_mpm/base/parameters.h>
#include <lme_mpm/output/moving_mean.h>
#include <lme_mpm/scenes/scene_tools.h>

#include <cmath>

namespace lme_mpm
{
namespace scenes
{
/**
 * Drop-weight impact on a notched beam: a beam of given length and depth, notched
 * from the middle of its bottom face, rests on two support cylinders at a span
 * symmetric about the notch; a rectangular hammer of given mass starts on its top face
 * at mid-span moving down at the impact velocity. The scene writes the bodies' shapes,
 * the notch (and an explicit crack on its centre line that keeps the notch faces
 * apart), the supports' (zero) velocity, the hammer's initial velocity and its
 * material's density from the hammer's mass.
 *
 * The hammer is a heavy block (its density set from the hammer's mass) with,
 * optionally, a head of its own material at its face: the tup's compliance, whose
 * modulus the shipped scene calibrates (scripts/calibrate_drop_weight_head.py).
 *
 * With Contact/Type = multi-field hammer and beam meet through contact and the
 * supports are fixed cylinders (prescribed bodies) in contact with the beam, or, with
 * Support kind = node sets, constrained node sets as on one field. With Contact/Type =
 * none (the paper's single velocity field) hammer and beam share the grid's nodes and
 * the supports are node sets: the vertical velocity of the node column through each
 * support's axis, from the beam's bottom face down, is held at zero.
 *
 * History: impact_force (the force on the hammer, upwards, N, for the real thickness:
 * the contact force with contact, the hammer's momentum rate on a single field) and
 * reaction_force (the upward forces of the supports on the beam, summed), both as
 * means over the force window (Output/Force window) ending at the row, and their
 * means over the row's interval (impact_force_mean, reaction_force_mean), beside
 * hammer_momentum_rate_mean and beam_momentum_rate_mean (the change of the body's
 * momentum over the row's interval divided by its length); cmod (crack-mouth
 * opening), damage_total, crack_tip and softening_front (how far the fully softened
 * crack and the front of softening have run up the ligament). Summary: the peaks of
 * the impact and reaction forces and their times from the first contact, the fronts'
 * largest speeds over a gauge length and their ratios to the Rayleigh speed, all
 * tracked after every step (observe()), so that they do not depend on the output
 * cadence.
 */
/// The drop-weight scene's entries, declared and read from this one list.
struct DropWeightEntries
{
  double length = 0.42, depth = 0.1, width = 0.1, span = 0.3, support = 0.01;
  double notch_depth = 0.05, notch_width = 0.0025, overhang = 0.015;
  double hammer_width = 0.05, hammer_height = 0.05, hammer_mass = 120.6;
  double head_height = 0, gap = 0, gauge = 0.01;
  unsigned int head_material = 0;
  double velocity            = 2.64;
  bool notch_crack           = true;
  std::string centre, beam, hammer, supports, support_kind = "auto";

  void entries(EntryList &list)
  {
    list.add("Beam centre", centre, "0.23, 0.025", Patterns::Anything(),
             "The middle of the beam's bottom face (x, y in m), where the notch starts.");
    list.add("Beam length", length, "0.42", Patterns::Double(),
             "The beam's length along x (m), > span.");
    list.add("Beam depth", depth, "0.1", Patterns::Double(),
             "The beam's depth along y (m), > 0.");
    list.add("Length", width, "0.1", Patterns::Double(),
             "3D only: the beam's width along z (m), from z = 0. In 2D it is "
             "Problem/Thickness.");
    list.add("Span", span, "0.3", Patterns::Double(),
             "The distance between the supports' axes (m), in (0, beam length).");
    list.add("Support radius", support, "0.01", Patterns::Double(),
             "The support cylinders' radius (m), > 0.");
    list.add("Notch depth", notch_depth, "0.05", Patterns::Double(),
             "The notch's depth from the bottom face (m), in (0, beam depth).");
    list.add("Notch width", notch_width, "0.0025", Patterns::Double(),
             "The notch's width (m), > 0; at least the particle spacing, or no particle "
             "is removed.");
    list.add("Notch crack", notch_crack, "true", Patterns::Bool(),
             "2D: an explicit crack (Cracks) on the notch's centre line from the notch "
             "crack overhang below the bottom face to the notch tip, so that the grid "
             "does not tie the notch faces together. Must be false in 3D.");
    list.add("Notch crack overhang", overhang, "0.015", Patterns::Double(),
             "How far the notch crack reaches below the bottom face (m); at least the "
             "shape functions' support radius; > 0.");
    list.add("Hammer width", hammer_width, "0.05", Patterns::Double(),
             "The hammer's width along x (m), > 0.");
    list.add("Hammer height", hammer_height, "0.05", Patterns::Double(),
             "The hammer's height along y (m), > 0.");
    list.add("Hammer mass", hammer_mass, "120.6", Patterns::Double(),
             "The hammer's mass (kg) over the real thickness (Problem/Thickness in 2D, "
             "Length in 3D); sets the density of the hammer's material, > 0.");
    list.add("Head height", head_height, "0", Patterns::Double(),
             "The height (m) of the hammer's head: the bottom of the hammer, made of "
             "Head material, in [0, Hammer height). It stands for the tup's own "
             "compliance (its nose, load cell and the local crushing under it); 0: the "
             "hammer is one block.");
    list.add("Head material", head_material, "0", Patterns::Integer(0),
             "The Material N of the head (its density given in the file, not set by the "
             "scene), not the hammer's Body N/Material; 0 without a head.");
    list.add("Hammer gap", gap, "0", Patterns::Double(),
             "The distance (m) between the hammer's face and the beam's top face at "
             "t = 0, >= 0. Particles fill the grid's cells at fixed points, so a gap "
             "below their spacing at the face places the same particles.");
    list.add("Impact velocity", velocity, "2.64", Patterns::Double(),
             "The hammer's downward speed at first contact (m/s), > 0.");
    list.add("Crack speed gauge length", gauge, "0.01", Patterns::Double(),
             "The crack speed is the time the crack tip takes to run from one multiple "
             "of this length above the notch tip to the next (m), > 0, as strain gauges "
             "glued along the ligament measure it.");
    list.add("Support kind", support_kind, "auto",
             Patterns::Selection("auto|cylinders|node sets"),
             "'cylinders': fixed rigid cylinders in contact with the beam (unilateral: "
             "the beam can lift off), which needs Contact/Type = multi-field; 'node "
             "sets': the vertical velocity of a node column under each support held at "
             "zero (bilateral, the paper's supports); 'auto': cylinders with contact, "
             "node sets without.");
    list.add("Beam", beam, "beam", Patterns::Anything(), "The Body N/Name of the beam.");
    list.add("Hammer", hammer, "hammer", Patterns::Anything(),
             "The Body N/Name of the hammer.");
    list.add("Supports", supports, "left, right", Patterns::Anything(),
             "The names of the supports at -x and +x: Body N/Name of two bodies with "
             "Contact/Type = multi-field, Boundary conditions/Constraint N/Name of two "
             "node sets with Contact/Type = none.");
  }
};

template <int dim>
class DropWeight : public Scene<dim>, private DropWeightEntries
{
public:
  /// The entries, declared by the registration.
  using Entries = DropWeightEntries;

  DropWeight(ParameterHandler &prm, const SceneContext<dim> &context)
      : DropWeightEntries(EntryList::parse<DropWeightEntries>(prm)),
        single_field(!context.contact),
        node_supports(support_kind == "node sets" ||
                      (support_kind == "auto" && !context.contact))
  {
    AssertThrow(!(single_field && support_kind == "cylinders"),
                ExcBadInput(entry("Support kind"),
                            "cylinders meet the beam through contact: they need "
                            "Contact/Type = multi-field"));
    if (dim == 2)
      width = context.thickness;
    const auto names = input::parse_names(supports, 2, entry("Supports"));
    left = names[0], right = names[1];
    const Point<2> c = input::parse_point<2>(centre, entry("Beam centre"));
    cx = c[0], cy = c[1];
    input::require_positive({{length, entry("Beam length")},
                             {depth, entry("Beam depth")},
                             {width, dim == 3 ? entry("Length") : "Problem/Thickness"},
                             {support, entry("Support radius")},
                             {overhang, entry("Notch crack overhang")},
                             {hammer_height, entry("Hammer height")},
                             {hammer_mass, entry("Hammer mass")},
                             {velocity, entry("Impact velocity")},
                             {gauge, entry("Crack speed gauge length")}});
    input::require_range(head_height, 0, hammer_height, false, entry("Head height"));
    AssertThrow(head_height < hammer_height,
                ExcBadInput(entry("Head height"),
                            "must be below Scene/drop weight/Hammer height = " +
                                number(hammer_height) +
                                " (the head is part of the hammer)"));
    AssertThrow(gap >= 0, ExcBadInput(entry("Hammer gap"), "must be >= 0"));
    AssertThrow((head_height > 0) == (head_material > 0),
                ExcBadInput(entry(head_height > 0 ? "Head material" : "Head height"),
                            "a head needs both Head height > 0 and Head material >= 1"));
    input::require_range(span, 0, length, true, entry("Span"));
    input::require_range(notch_depth, 0, depth, true, entry("Notch depth"));
    input::require_range(notch_width, 0, span, true, entry("Notch width"));
    input::require_range(hammer_width, 0, length, true, entry("Hammer width"));
    if (dim == 3)
      AssertThrow(!notch_crack,
                  ExcBadInput(entry("Notch crack"), "must be false in 3D (explicit "
                                                    "cracks exist in 2D only)"));
  }

  void write_entries(EntryWriter &writer) override
  {
    // The crack mouth's clip gauge: material points 2 mm either side of the notch's
    // faces, 1.5 mm above the beam's bottom, the particles within 1.5 mm of each.
    const double g = 0.5 * notch_width + 0.002, r = 0.0015;
    add_opening_gauge(writer, gauge_name, Point<2>(cx - g, cy + r),
                      Point<2>(cx + g, cy + r), r);
    writer.set_body(
        beam, "Shape",
        box_shape<dim>(cx - 0.5 * length, cy, cx + 0.5 * length, cy + depth, width),
        entry("Beam"));
    // The notch, open below the bottom face by a margin that holds no particle.
    writer.set_body(beam, "Holes",
                    box_shape<dim>(cx - 0.5 * notch_width, cy - 0.5 * notch_width,
                                   cx + 0.5 * notch_width, cy + notch_depth, width),
                    entry("Notch depth"));
    if (notch_crack)
    {
      const std::string line = number(cx) + ", " + number(cy - overhang) + ", " +
                               number(cx) + ", " + number(cy + notch_depth);
      set_notch_crack(writer, beam, line, entry("Notch crack"));
    }
    for (const int side : {-1, 1})
      write_support(writer, side < 0 ? left : right, cx + 0.5 * side * span);
    const double face = cy + depth + gap;
    writer.set_body(hammer, "Shape",
                    box_shape<dim>(cx - 0.5 * hammer_width, face, cx + 0.5 * hammer_width,
                                   face + hammer_height, width),
                    entry("Hammer"));
    writer.set_body(hammer, "Initial velocity/Function expression",
                    dim == 2 ? "0; " + number(-velocity)
                             : "0; " + number(-velocity) + "; 0",
                    entry("Impact velocity"));
    // The hammer's body material gets the density that gives the hammer its mass,
    // with the head's own mass taken off.
    const std::string material =
        writer.get(input::subsection_name("Body", writer.body(hammer, entry("Hammer"))) +
                   "/Material");
    double head_mass = 0;
    if (head_height > 0)
    {
      const auto n_materials = std::stoul(writer.get("Problem/Number of materials"));
      AssertThrow(head_material <= n_materials,
                  ExcBadInput(entry("Head material"),
                              "must be between 1 and Problem/Number of materials = " +
                                  std::to_string(n_materials)));
      AssertThrow(std::to_string(head_material) != material,
                  ExcBadInput(entry("Head material"),
                              "must differ from the hammer's Body N/Material (" +
                                  material +
                                  "), whose density the scene sets from Hammer mass"));
      const std::string head = "Material " + std::to_string(head_material);
      head_mass =
          std::stod(writer.get(head + "/Density")) * hammer_width * head_height * width;
      AssertThrow(head_mass < hammer_mass,
                  ExcBadInput(entry("Head material"),
                              "the head (" + head + "/Density over Head height) weighs " +
                                  number(head_mass) +
                                  " kg, not less than Scene/drop weight/Hammer mass"));
      writer.set_body(hammer, "Material zones",
                      std::to_string(head_material) + ": " +
                          box_shape<dim>(cx - 0.5 * hammer_width, face,
                                         cx + 0.5 * hammer_width, face + head_height,
                                         width),
                      entry("Head height"));
    }
    const double density = (hammer_mass - head_mass) /
                           (hammer_width * (hammer_height - head_height) * width);
    writer.set("Material " + material + "/Density", number(density), entry("Hammer mass"),
               " for the hammer's material");
    // The beam's Rayleigh speed, the scale of its crack speed (linear elastic beams).
    fracture_energy = fracture_energy_of(writer, writer.body(beam, entry("Beam")));
    const std::string concrete =
        "Material " +
        writer.get(input::subsection_name("Body", writer.body(beam, entry("Beam"))) +
                   "/Material");
    if (writer.get(concrete + "/Model") == "linear elastic")
      rayleigh_speed = rayleigh_wave_speed(
          std::stod(writer.get(concrete + "/linear elastic/Young's modulus")),
          std::stod(writer.get(concrete + "/linear elastic/Poisson's ratio")),
          std::stod(writer.get(concrete + "/Density")),
          dim == 2 && writer.get("Problem/Plane assumption") == "plane stress");
  }

  void check(const SceneState<dim> &state) const override
  {
    (void)body_index(state, beam, entry("Beam"));
    (void)body_index(state, hammer, entry("Hammer"));
    if (node_supports)
    {
      (void)constraint_named(state, left, entry("Supports"));
      (void)constraint_named(state, right, entry("Supports"));
    }
    else
    {
      (void)body_index(state, left, entry("Supports"));
      (void)body_index(state, right, entry("Supports"));
    }
  }

  void write_history_header(std::ostream &out) const override
  {
    out << ",impact_force,impact_force_mean,hammer_momentum_rate_mean,"
           "beam_momentum_rate_mean,reaction_force,reaction_force_mean,cmod,"
           "damage_total,crack_tip,softening_front";
  }

  void write_history_row(std::ostream &out, const SceneState<dim> &state) const override
  {
    const ParticleStore<dim> &p = *state.particles;
    const unsigned int b        = body_index(state, beam, entry("Beam"));
    const unsigned int h        = body_index(state, hammer, entry("Hammer"));
    double momentum = 0, beam_momentum = 0;
    for (std::size_t i = 0; i < p.size(); ++i)
      if (p.body_id[i] == h)
        momentum += p.mass[i] * p.velocity[i][1];
      else if (p.body_id[i] == b)
        beam_momentum += p.mass[i] * p.velocity[i][1];
    // The means over the row's interval: momentum changes and impulses over its
    // length (0 in the first row).
    const double interval = state.time - last_row.time;
    const auto rate       = [&](const double now, const double before)
    { return interval > 0 ? (now - before) / interval : 0.0; };
    const double hammer_rate     = rate(momentum, last_row.momentum);
    const double beam_rate       = rate(beam_momentum, last_row.beam_momentum);
    const double support_impulse = node_supports ? supports_impulse(state) : 0.0;
    double impact_mean = hammer_rate, reaction_mean = 0;
    if (!single_field)
      impact_mean = (*state.contact_force_means)[h][1];
    if (node_supports)
      reaction_mean = rate(support_impulse, last_row.support_impulse);
    else
    {
      const auto &force = *state.contact_force_means;
      reaction_mean     = -force[body_index(state, left, entry("Supports"))][1] -
                      force[body_index(state, right, entry("Supports"))][1];
    }
    last_row          = {state.time, momentum, beam_momentum, support_impulse};
    const double cmod = gauge_reading(state, gauge_name);
    out << "," << impact << "," << impact_mean << "," << hammer_rate << "," << beam_rate
        << "," << reaction << "," << reaction_mean << "," << cmod << ","
        << damaged_volume(p, b) << "," << crack.position << "," << softening.position;
  }

  void observe(const SceneState<dim> &state) override
  {
    const ParticleStore<dim> &p = *state.particles;
    const unsigned int b        = body_index(state, beam, entry("Beam"));
    const unsigned int h        = body_index(state, hammer, entry("Hammer"));
    const double dt = state.step_length, t = state.time;
    // This step's forces where no contact force gives them: on one field the
    // hammer's momentum rate over the step, and the node-set supports' reactions;
    // their means over the force window.
    if (windows.size() == 0)
      windows.reset(2, state.force_window);
    double step_values[2] = {0, 0};
    if (single_field)
    {
      double momentum = 0;
      for (std::size_t i = 0; i < p.size(); ++i)
        if (p.body_id[i] == h && state.owned(i))
          momentum += p.mass[i] * p.velocity[i][1];
      momentum       = state.ranks->sum(momentum);
      step_values[0] = (momentum - step_momentum) / dt;
      step_momentum  = momentum;
    }
    if (node_supports)
      step_values[1] = constraint_named(state, left, entry("Supports")).reaction()[1] +
                       constraint_named(state, right, entry("Supports")).reaction()[1];
    windows.book(step_values, dt);
    impact = windows.mean(0), reaction = windows.mean(1);
    if (!single_field)
      impact = (*state.contact_forces)[h][1];
    if (!node_supports)
    {
      const auto &force = *state.contact_forces;
      reaction          = -force[body_index(state, left, entry("Supports"))][1] -
                 force[body_index(state, right, entry("Supports"))][1];
    }
    if (first_contact < 0 && std::abs(impact) > 0)
      first_contact = t - dt;
    if (first_contact >= 0)
    {
      if (impact > peak_impact)
        peak_impact = impact, time_of_peak_impact = t - first_contact;
      if (reaction > peak_reaction)
        peak_reaction = reaction, time_of_peak_reaction = t - first_contact;
    }
    // A front moves only when a particle of the beam crosses its damage level:
    // counted every step (both levels in one pass), located again (over every
    // particle) when the count changes.
    const Point<2> notch_tip(cx, cy + notch_depth);
    const double thickness = dim == 2 ? width : 1.0;
    std::vector<double> counts(2, 0.0);
    for (std::size_t i = 0; i < p.size(); ++i)
      if (p.body_id[i] == b && p.damage[i] >= softening_onset && state.owned(i))
      {
        counts[1] += 1;
        if (p.damage[i] >= crack_level)
          counts[0] += 1;
      }
    state.ranks->sum(counts);
    for (GaugedFront *front : {&crack, &softening})
    {
      const double level = front == &crack ? crack_level : softening_onset;
      const double count = counts[front == &crack ? 0 : 1];
      if (count == front->count)
        continue;
      front->count                  = count;
      const ParticleStore<dim> &all = state.all_particles();
      const double distance         = state.ranks->max(
                  all.size() > 0 ? crack_tip_distance(all, b, thickness, notch_tip,
                                                      Tensor<1, 2>({0.0, 1.0}), level)
                                 : 0.0);
      front->advance(distance, t - dt, t, gauge);
    }
  }

  void add_results(const SceneState<dim> &state,
                   std::map<std::string, double> &results) const override
  {
    if (first_contact < 0)
      return;
    // The ligament's crack: from the notch tip to the crack tip, its band (damage >=
    // 0.5) and the energy dissipated within one band width of the ligament, over G_F
    // times its area; what was dissipated farther away (under the hammer, over the
    // supports) is the off-crack share.
    const ParticleStore<dim> &p = *state.particles;
    const unsigned int b        = body_index(state, beam, entry("Beam"));
    const double thickness      = dim == 2 ? width : 1.0;
    const Point<2> notch_tip(cx, cy + notch_depth);
    const CrackPath path = crack_path(p, b, thickness, 0.5, &notch_tip);
    const CrackBand band = crack_band(p, b, path, {notch_tip, Point<2>(cx, cy + depth)});
    add_crack_band(band, results);
    const double area     = crack.position * thickness;
    results["crack_area"] = area;
    if (fracture_energy > 0 && area > 0)
      results["fracture_energy_ratio"] = band.on_crack / (fracture_energy * area);
    results["peak_impact_force"]           = peak_impact;
    results["time_of_peak_impact_force"]   = time_of_peak_impact;
    results["peak_reaction_force"]         = peak_reaction;
    results["time_of_peak_reaction_force"] = time_of_peak_reaction;
    results["time_of_first_contact"]       = first_contact;
    results["crack_tip"]                   = crack.position;
    results["max_crack_speed"]             = crack.max_speed;
    results["softening_front"]             = softening.position;
    results["max_softening_front_speed"]   = softening.max_speed;
    if (rayleigh_speed > 0)
    {
      results["max_crack_speed_over_rayleigh"] = crack.max_speed / rayleigh_speed;
      results["max_softening_front_speed_over_rayleigh"] =
          softening.max_speed / rayleigh_speed;
    }
  }

  void serialize(Archive &ar) override
  {
    ar(last_row, step_momentum, impact, reaction, first_contact, peak_impact,
       time_of_peak_impact, peak_reaction, time_of_peak_reaction, crack, softening);
    windows.serialize(ar);
  }

private:
  static std::string entry(const std::string &name)
  {
    return "Scene/drop weight/" + name;
  }

  /// The support named @p name with its axis at x = @p axis: a cylinder (contact) or
  /// the node column under the beam's face (one velocity field).
  void write_support(EntryWriter &writer, const std::string &name,
                     const double axis) const
  {
    if (!node_supports)
    {
      writer.set_body(name, "Shape",
                      cylinder_shape<dim>(axis, cy - support, support, width),
                      entry("Supports"));
      writer.set_body(name, "Prescribed velocity/Function expression",
                      ramped_velocity<dim>(0, 0, 0), entry("Supports"));
      return;
    }
    AssertThrow(!writer.has_body(name) && writer.n_constraints() >= 2,
                ExcBadInput(entry("Supports"),
                            "supports as node sets (Contact/Type = none or Support kind "
                            "= node sets): give "
                            "two Boundary conditions/Constraint N named '" +
                                left + "' and '" + right +
                                "' and no body of these names "
                                "(prm/drop_weight_single_field.prm)"));
    // A knife edge under the face: the grid nodes within a quarter of the support
    // radius of its axis (one column on the scene's grids), from the face down to
    // where the cylinder would end.
    const double a = 0.25 * support;
    const std::string box =
        dim == 2 ? number(axis - a) + ", " + number(cy - 2 * support) + ", " +
                       number(axis + a) + ", " + number(cy + 1e-9 * depth)
                 : number(axis - a) + ", " + number(cy - 2 * support) + ", 0, " +
                       number(axis + a) + ", " + number(cy + 1e-9 * depth) + ", " +
                       number(width);
    const std::string section =
        "Boundary conditions/" +
        input::subsection_name("Constraint", writer.constraint(name, entry("Supports")));
    writer.set(section + "/Box", box, entry("Supports"));
    writer.set(section + "/Components", "y", entry("Supports"));
  }

  /// The supports' vertical impulse since the start (node-set supports).
  double supports_impulse(const SceneState<dim> &state) const
  {
    return constraint_named(state, left, entry("Supports")).impulse()[1] +
           constraint_named(state, right, entry("Supports")).impulse()[1];
  }

  bool single_field, node_supports;
  double cx = 0.23, cy = 0.025;
  static constexpr const char *gauge_name = "cmod";
  std::string left, right;
  /// What the last history row saw, for the means over the next row's interval.
  struct RowState
  {
    double time = 0, momentum = 0, beam_momentum = 0, support_impulse = 0;
  };
  mutable RowState last_row;
  // Tracked after every step (kept in checkpoints): the hammer's momentum (one
  // field), the step's forces' means over the force window, the first contact and the
  // peaks.
  MovingMean windows;
  double step_momentum = 0, impact = 0, reaction = 0;
  double first_contact = -1;
  double peak_impact = 0, time_of_peak_impact = 0;
  double peak_reaction = 0, time_of_peak_reaction = 0;
  /// A front running up the ligament, timed as strain gauges a gauge length apart
  /// would time it.
  struct GaugedFront
  {
    /// Its distance above the notch tip after the last step, the gauge levels it has
    /// passed, when it passed the last, and its fastest run between two levels.
    double position = 0, last_pass = 0, max_speed = 0;
    unsigned int passed = 0;
    /// Particles at the front's damage level when it was last located.
    double count = 0;

    /// The front at @p now is at @p distance; it was at position at @p before.
    void advance(const double distance, const double before, const double now,
                 const double gauge)
    {
      while (distance >= (passed + 1) * gauge)
      {
        // When it passed the level, interpolated linearly over the step.
        const double level = (passed + 1) * gauge;
        const double t =
            before + (now - before) * (level - position) / (distance - position);
        if (passed > 0)
          max_speed = std::max(max_speed, gauge / (t - last_pass));
        last_pass = t, ++passed;
      }
      position = distance;
    }
  };
  // The fully softened crack and the front where softening has started (damage above
  // this), which is what a gauge on the ligament sees: its strain peaks there.
  static constexpr double softening_onset = 1e-9, crack_level = 0.99;
  GaugedFront crack, softening;
  double rayleigh_speed = 0, fracture_energy = 0;
};
} // namespace scenes
} // namespace lme_mpm

using lme_mpm::scenes::DropWeight;
LME_MPM_REGISTER_SCENE(DropWeight, "drop weight",
                       "a notched beam on two supports struck at mid-span by a hammer "
                       "(Impact velocity), in contact or on one velocity field; "
                       "writes the bodies' shapes, the hammer's "
                       "velocity and density, reports the peak impact and reaction "
                       "forces and their times.")
