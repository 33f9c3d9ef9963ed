#ifndef LME_MPM_SIMULATION_EXPLICIT_STEP_H
#define LME_MPM_SIMULATION_EXPLICIT_STEP_H

#include <deal.II/base/tensor.h>

#include <lme_mpm/base/stage_timer.h>
#include <lme_mpm/simulation/parts.h>
#include <lme_mpm/simulation/run_guard.h>
#include <lme_mpm/solver/explicit_newmark.h>

#include <cstddef>
#include <limits>
#include <vector>

namespace lme_mpm
{
/// What one step hands back to the time loop.
struct StepResult
{
  /// The lowest index of a particle that went wrong (the number of particles: none).
  std::size_t first_bad = 0;
  /// The work of the external forces over the step (J): the constraints' reactions,
  /// the body force and the prescribed bodies' contact, summed over the ranks.
  double external_work = 0;
  /// The fastest particle's speed after the step (m/s, on this rank: the conductor
  /// reduces it with its other maxima in one collective call).
  double max_speed = 0;
};

/**
 * One explicit Newmark step (doc/theory.md, doc/design.md), stage by stage: crack
 * growth, particles located and sorted, shape functions and particles to grid, the
 * displacement rates (predictor) with prescribed bodies, crack faces, constraints,
 * mass corrections and contact, strains and stresses, fracture, forces, the
 * accelerations (corrector) with the same, and grid to particles; then the particle
 * exchange of a distributed run. Every stage is timed (StageTimer). Before the first
 * step it sets the accelerations a^0 = M^-1 f(u^0).
 */
template <int dim>
class ExplicitStep
{
public:
  ExplicitStep(SimulationParts<dim> &parts, const RunGuard<dim> &guard);

  /**
   * The step's constants: the time step @p dt, the mass below which a field is
   * empty, and for growing cracks the farthest a support reaches and the smallest
   * particle spacing.
   */
  void set_up(double dt, double mass_tolerance, double crack_reach,
              double particle_spacing);

  /**
   * Advances the particles from time @p t to t + dt; @p step is the number of steps
   * done. Stops the run (RunGuard) if a particle left the grid; a particle that the
   * step made unstable is reported in the result.
   */
  StepResult advance(double t, unsigned int step);
  /// The length of the next step (TimeStepControl).
  void set_time_step(const double step) { dt = step; }
  /// The fastest particle's speed now (m/s, over the ranks).
  double fastest_particle() const;
  /// A distributed run's particle exchange, after the step (nothing on one rank).
  void exchange_particles();

  /// A resumed run has its accelerations from the checkpoint.
  void mark_initialised() { initialised = true; }
  const ExplicitNewmark &scheme() const { return newmark; }
  double mass_tolerance() const { return min_mass; }
  /// The wall time of each stage.
  const StageTimer &stages() const { return timer; }
  /// The particle exchange's seconds (distributed runs).
  double exchange_seconds() const { return timer.seconds(stage.exchange); }

private:
  /// What the corrector stage hands to the particle update.
  struct Corrected
  {
    /// M a where the mass matrix is not lumped (null otherwise), for the reactions.
    const std::vector<Tensor<1, dim>> *mass_times_acceleration = nullptr;
    /// The work the prescribed bodies did on the others through contact (J).
    double contact_work = 0;
    /// The rigid exact surfaces' work on the particles (J, over the ranks).
    double rigid_work = 0;
  };

  void initialise(double t, unsigned int step);
  void grow_cracks();
  void locate_and_sort(double t, unsigned int step);
  void particles_to_grid();
  /// True if a part besides the transfers reads the step's full connectivity rows.
  bool full_rows_needed() const;
  void predict_rates(double t_half);
  void stresses_and_forces(double t_new);
  /// Accelerations with contact and constraints.
  Corrected correct_accelerations(double t_new);
  /// Reactions, then the Newmark corrector on the particles.
  StepResult update_particles(double t, const Corrected &corrected);

  /// Prescribed bodies, then constraints: the rates at @p t.
  void impose_rates(std::vector<Tensor<1, dim>> &x, double t) const;
  /// The same on accelerations.
  void impose_accelerations(std::vector<Tensor<1, dim>> &x, double t) const;
  /// Half-width of the central difference that gives prescribed accelerations.
  double derivative_step() const { return 1e-3 * dt; }

  SimulationParts<dim> &parts;
  const RunGuard<dim> &guard;
  ExplicitNewmark newmark;
  double dt = 0, min_mass = 0, crack_reach = 0;
  double particle_spacing = std::numeric_limits<double>::max();
  /// a^0 = M^-1 f(u^0) is on the particles (computed, or read from a checkpoint).
  bool initialised = false;

  StageTimer timer;
  struct StageIds
  {
    unsigned int crack_growth, locate, to_grid, rates, stresses_and_forces, stresses,
        fracture, forces, accelerations, to_particles, contact, exchange, mass_solve;
  } stage{};
  /// The run's mass solve (MassSolve) on the lumped solution in @p x, timed in its
  /// own stage when it solves M_C.
  void solve_mass(std::vector<Tensor<1, dim>> &x, const std::vector<Tensor<1, dim>> &rhs,
                  const typename MassSolve<dim>::Constrain &constrain, const char *what,
                  double t);
};
} // namespace lme_mpm

#endif
