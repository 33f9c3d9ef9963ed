#ifndef LME_MPM_SIMULATION_SIMULATION_H
#define LME_MPM_SIMULATION_SIMULATION_H

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>

#include <lme_mpm/base/archive.h>
#include <lme_mpm/simulation/explicit_step.h>
#include <lme_mpm/simulation/parts.h>
#include <lme_mpm/simulation/run_guard.h>
#include <lme_mpm/simulation/run_output.h>
#include <lme_mpm/solver/run_parameters.h>
#include <lme_mpm/solver/time_step_control.h>

#include <chrono>
#include <cstdint>
#include <iostream>
#include <limits>
#include <map>
#include <string>

namespace lme_mpm
{
/**
 * One MPM run, the conductor: builds the parts (SimulationParts) from the parameter
 * file and wires them, then runs the time loop, calling the explicit step
 * (ExplicitStep), the output (RunOutput), the run guard (RunGuard) and the checkpoint
 * in turn. A feature lands in the part it belongs to; this class only calls it
 * (doc/design.md).
 */
template <int dim>
class Simulation
{
public:
  static void declare_parameters(ParameterHandler &prm, const ParameterCounts &counts);

  /// Parses and checks everything; throws naming the entry on bad input. Writes nothing.
  Simulation(ParameterHandler &prm, const ParameterCounts &counts,
             std::ostream &console = std::cout);

  /// How the run was started (kept in its output: parameters.prm, summary.json).
  void keep_record(RunRecord record) { output.keep_record(std::move(record)); }

  /// Runs to the end time. Returns the summary values (also in summary.json).
  std::map<std::string, double> run();

  /// Advances one time step (public for tests).
  void step();

  double time() const { return t; }
  double time_step() const { return dt; }
  /// This rank's particles (owned ones and ghosts; all of them on one rank).
  const ParticleStore<dim> &particles() const { return parts.particles; }
  /// The split over MPI ranks.
  const Decomposition<dim> &decomposition() const { return parts.ranks; }
  const BackgroundGrid<dim> &grid() const { return parts.grid; }
  /**
   * Continues the run saved in @p directory/checkpoint.bin (written by a run of the same
   * parameter file); output goes on in that directory. Call before run().
   */
  void resume_from(const std::string &directory);

  /// A hash of every particle field and the time: equal states, equal sums (FNV-1a).
  std::uint64_t state_checksum();

  /// Kinetic, strain, dissipated energy, external work and total energy (J) now.
  std::map<std::string, double> energies() const { return output.energies(); }

private:
  // Set-up, in order.
  void setup_scene(ParameterHandler &prm, const ParameterCounts &counts);
  /// Creates the shape functions and sets the particle state the run keeps.
  void setup_shape_functions(ParameterHandler &prm);
  void setup_particles(ParameterHandler &prm, const ParameterCounts &counts);
  void check_initial_motion(const std::vector<std::string> &body_sections) const;
  /// What depends on the shape functions and the particles: the crack band, the
  /// explicit cracks' fields.
  void couple_shape_functions();
  void setup_bodies_and_contact(ParameterHandler &prm, const ParameterCounts &counts);
  /// Sets up the split over MPI ranks and keeps this rank's particles.
  void distribute();

  void advance_to_end(TimerOutput &timer, std::chrono::steady_clock::time_point start);
  /// Ends a run that failed inside the loop: its message (what the output keeps).
  std::string end_failed_run(const std::exception &e);
  /// Writes summary.json; if it cannot be written, removes any earlier one and turns
  /// @p status and @p message into the failure's.
  void write_summary(const RunSummary &summary, std::uint64_t checksum,
                     std::string &status, std::string &message) const;
  /// Turns @p status and @p message into those of a run that could not write a file
  /// (@p why: the file and the reason).
  static void fail_on_write(const std::string &why, std::string &status,
                            std::string &message);

  // Checkpoints (checkpoint_restart.cc).
  void serialize(Archive &ar);
  void write_checkpoint();
  bool checkpoint_due(std::chrono::steady_clock::time_point last) const;
  /// True if Checkpoint/Every steps or Every seconds asks for checkpoints.
  bool checkpoints_on() const
  {
    return parts.parameters.checkpoint_every_steps > 0 ||
           parts.parameters.checkpoint_every_seconds > 0;
  }
  /// Where this rank's checkpoint goes in @p directory.
  std::string checkpoint_file(const std::string &directory) const;

  SimulationParts<dim> parts;
  RunGuard<dim> guard;
  ExplicitStep<dim> stepper;
  RunOutput<dim> output;

  /// The steps' lengths; dt is the last one's, max_speed the fastest particle's speed
  /// after it.
  TimeStepControl clock;
  double dt = 0, t = 0, max_speed = 0;
  /// The largest signal number any rank had received at the last step (0: none).
  int interrupt_signal = 0;
  /// The step's maxima over the ranks, reduced together: the fastest particle's
  /// speed, the interrupt signal and whether a particle went wrong (1) or not (0).
  std::vector<double> step_maxima = std::vector<double>(3);
  unsigned int step_count         = 0;
  /// Particles in the whole run (on all ranks).
  std::size_t n_particles = 0;
  bool resumed            = false;
  // Farthest a support reaches (for the cracks' second fields) and the smallest
  // particle spacing of the bodies (for their growth).
  double crack_reach = 0, particle_spacing = std::numeric_limits<double>::max();
  /// Per body: how far its outermost particles sit inside a face of their cells (m),
  /// for the rigid surfaces' contact
  std::vector<double> face_depths;
};
} // namespace lme_mpm

#endif
