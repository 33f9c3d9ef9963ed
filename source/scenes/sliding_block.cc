#include <lme_mpm/base/input.h>
#include <lme_mpm/base/parameters.h>
#include <lme_mpm/scenes/scene.h>
#include <lme_mpm/scenes/scene_tools.h>

#include <cmath>

namespace lme_mpm
{
namespace scenes
{
/**
 * A block on a slab whose surface is the grid's x direction, under gravity tilted by
 * the incline angle from the slab's normal (+y): the inclined-plane problem without
 * tilting the grid. Reports the block's mass-weighted mean displacement along the
 * slab, which with Coulomb friction mu is 0.5 g (sin theta - mu cos theta) t^2 while
 * tan theta > mu, and zero otherwise (sliding_distance_exact, which also follows a
 * gravity ramp, Problem/Body force ramp time).
 */
template <int dim>
class SlidingBlock : public Scene<dim>
{
public:
  /// The scene's entries, declared and read from this one list.
  struct Entries
  {
    double angle = 30, gravity = 9.81;
    std::string block;
    void entries(EntryList &list)
    {
      list.add("Incline angle", angle, "30", Patterns::Double(),
               "Angle (degrees) between gravity and the slab's normal (+y), in [0, 90).");
      list.add("Gravity", gravity, "9.81", Patterns::Double(),
               "Magnitude of gravity (m/s^2), positive.");
      list.add("Block", block, "block", Patterns::Anything(),
               "The Body N/Name of the block.");
    }
  };
  SlidingBlock(ParameterHandler &prm, const SceneContext<dim> &)
      : in(EntryList::parse<Entries>(prm))
  {
    input::require_range(in.angle, 0, 90, false, entry("Incline angle"));
    AssertThrow(in.angle < 90,
                ExcBadInput(entry("Incline angle"), "must be below 90 degrees"));
    AssertThrow(std::isfinite(in.gravity) && in.gravity > 0,
                ExcBadInput(entry("Gravity"), "must be finite and positive"));
  }

  /// The exact distance needs the block's friction.
  void write_entries(EntryWriter &writer) override
  {
    friction = std::stod(writer.get("Contact/Friction coefficient"));
  }

  void adjust(RunParameters<dim> &run) const override
  {
    AssertThrow(
        run.body_force.norm() == 0,
        ExcBadInput("Problem/Body force", "the sliding-block scene sets gravity from " +
                                              entry("Incline angle") + " and " +
                                              entry("Gravity") + ": leave it at 0"));
    const double theta = in.angle * M_PI / 180;
    run.body_force     = Tensor<1, dim>();
    run.body_force[0]  = in.gravity * std::sin(theta);
    run.body_force[1]  = -in.gravity * std::cos(theta);
  }

  void check(const SceneState<dim> &state) const override { (void)block_index(state); }

  void add_results(const SceneState<dim> &state,
                   std::map<std::string, double> &results) const override
  {
    const unsigned int body     = block_index(state);
    const ParticleStore<dim> &p = *state.particles;
    double moment = 0, mass = 0;
    for (std::size_t i = 0; i < p.size(); ++i)
      if (p.body_id[i] == body)
      {
        moment += p.mass[i] * (p.position[i][0] - p.reference_position[i][0]);
        mass += p.mass[i];
      }
    results["sliding_distance"] = moment / mass;
    results["sliding_distance_exact"] =
        exact_distance(state.time, state.run->body_force_ramp);
  }

  /**
   * The rigid block's distance at time @p T under gravity that grows linearly over
   * the ramp time t_r = @p ramp (Problem/Body force ramp time): with a = g (sin theta -
   * mu cos theta) > 0 the block slides from the start, x = a t^3 / (6 t_r) during the
   * ramp and a (T^2 / 2 - T t_r / 2 + t_r^2 / 6) after it; 0 if a <= 0.
   */
  double exact_distance(const double T, const double ramp) const
  {
    const double theta = in.angle * M_PI / 180;
    const double a     = in.gravity * (std::sin(theta) - friction * std::cos(theta));
    if (!(a > 0))
      return 0;
    if (ramp <= 0)
      return 0.5 * a * T * T;
    if (T <= ramp)
      return a * T * T * T / (6 * ramp);
    return a * (0.5 * T * T - 0.5 * T * ramp + ramp * ramp / 6);
  }

private:
  static std::string entry(const std::string &name)
  {
    return "Scene/sliding block/" + name;
  }
  unsigned int block_index(const SceneState<dim> &state) const
  {
    return body_index(state, in.block, entry("Block"));
  }

  Entries in;
  double friction = 0;
};
} // namespace scenes
} // namespace lme_mpm

using lme_mpm::scenes::SlidingBlock;
LME_MPM_REGISTER_SCENE(SlidingBlock, "sliding block",
                       "a block on a slab along x under gravity tilted by the Incline "
                       "angle; reports sliding_distance, the block's mean displacement "
                       "along the slab (m).")
