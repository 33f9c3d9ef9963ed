#include <lme_mpm/base/input.h>
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
  static void declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Incline angle", "30", Patterns::Double(),
                      "Sliding block: angle (degrees) between gravity and the slab's "
                      "normal (+y), in [0, 90).");
    prm.declare_entry("Gravity", "9.81", Patterns::Double(),
                      "Sliding block: magnitude of gravity (m/s^2), positive.");
    prm.declare_entry("Block", "block", Patterns::Anything(),
                      "Sliding block: the Body N/Name of the block.");
  }

  SlidingBlock(ParameterHandler &prm, const SceneContext<dim> &)
  {
    angle   = prm.get_double("Incline angle");
    gravity = prm.get_double("Gravity");
    block   = input::trim(prm.get("Block"));
    // The exact distance needs the block's friction (Contact/Friction coefficient).
    prm.leave_subsection();
    prm.enter_subsection("Contact");
    friction = prm.get_double("Friction coefficient");
    prm.leave_subsection();
    prm.enter_subsection("Scene");
    input::require_range(angle, 0, 90, false, "Scene/Incline angle");
    AssertThrow(angle < 90,
                ExcBadInput("Scene/Incline angle", "must be below 90 degrees"));
    AssertThrow(std::isfinite(gravity) && gravity > 0,
                ExcBadInput("Scene/Gravity", "must be finite and positive"));
  }

  void adjust(RunParameters<dim> &run) const override
  {
    AssertThrow(run.body_force.norm() == 0,
                ExcBadInput("Problem/Body force",
                            "the sliding-block scene sets gravity from Scene/Incline "
                            "angle and Scene/Gravity: leave it at 0"));
    const double theta = angle * M_PI / 180;
    run.body_force     = Tensor<1, dim>();
    run.body_force[0]  = gravity * std::sin(theta);
    run.body_force[1]  = -gravity * std::cos(theta);
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
    const double theta = angle * M_PI / 180;
    const double a     = gravity * (std::sin(theta) - friction * std::cos(theta));
    if (!(a > 0))
      return 0;
    if (ramp <= 0)
      return 0.5 * a * T * T;
    if (T <= ramp)
      return a * T * T * T / (6 * ramp);
    return a * (0.5 * T * T - 0.5 * T * ramp + ramp * ramp / 6);
  }

private:
  unsigned int block_index(const SceneState<dim> &state) const
  {
    return body_index(state, block, "Scene/Block");
  }

  double angle = 30, gravity = 9.81, friction = 0;
  std::string block;
};
} // namespace scenes
} // namespace lme_mpm

using lme_mpm::scenes::SlidingBlock;
LME_MPM_REGISTER_SCENE(SlidingBlock, "sliding block",
                       "a block on a slab along x under gravity tilted by Scene/Incline "
                       "angle; reports sliding_distance, the block's mean displacement "
                       "along the slab (m).")
