#ifndef LME_MPM_SOLVER_SIMULATION_H
#define LME_MPM_SOLVER_SIMULATION_H

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>

#include <lme_mpm/base/archive.h>
#include <lme_mpm/base/stage_timer.h>
#include <lme_mpm/boundary/node_constraints.h>
#include <lme_mpm/contact/body_contact.h>
#include <lme_mpm/distributed/decomposition.h>
#include <lme_mpm/fracture/crack_set.h>
#include <lme_mpm/fracture/fracture_coupling.h>
#include <lme_mpm/grid/background_grid.h>
#include <lme_mpm/materials/material_set.h>
#include <lme_mpm/output/energy_balance.h>
#include <lme_mpm/output/exact_solution.h>
#include <lme_mpm/output/grid_output.h>
#include <lme_mpm/output/history_file.h>
#include <lme_mpm/output/particle_output.h>
#include <lme_mpm/output/peak_force.h>
#include <lme_mpm/output/probes.h>
#include <lme_mpm/output/run_summary.h>
#include <lme_mpm/particles/particle_store.h>
#include <lme_mpm/scenes/scene.h>
#include <lme_mpm/shape_functions/crack_band.h>
#include <lme_mpm/shape_functions/shape_function.h>
#include <lme_mpm/solver/crack_face_contact.h>
#include <lme_mpm/solver/explicit_newmark.h>
#include <lme_mpm/solver/grid_transfer.h>
#include <lme_mpm/solver/run.h>
#include <lme_mpm/solver/run_parameters.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <string>

namespace lme_mpm
{
/// A run stopped on purpose before its end time ("Time/Maximum steps").
DeclException2(ExcStepLimit, unsigned int, double,
               << "Stopped after " << arg1 << " steps at time " << arg2
               << " s, as 'Time/Maximum steps' asks; the end time was not reached");
/// A run that became unphysical or unstable; the message says where and why.
DeclException5(ExcRunAborted, unsigned int, double, unsigned int, std::string,
               std::string, << "Run stopped at step " << arg1 << ", time " << arg2
                            << ": particle " << arg3 << " at " << arg4 << ": " << arg5);

/**
 * One MPM run: owns the grid, the particles and the parts that act on them, and
 * advances them with the explicit Newmark predictor-corrector (doc/theory.md), one
 * named stage after another (doc/design.md), writing VTU/PVD, history.csv and
 * summary.json to the output directory.
 */
template <int dim>
class Simulation
{
public:
  static void declare_parameters(ParameterHandler &prm, const ParameterCounts &counts);

  /// Parses and checks everything; throws naming the entry on bad input. Writes nothing.
  Simulation(ParameterHandler &prm, const ParameterCounts &counts,
             std::ostream &console = std::cout);

  /// Runs to the end time. Returns the summary values (also in summary.json).
  std::map<std::string, double> run();

  /// Advances one time step (public for tests).
  void step();

  double time() const { return t; }
  double time_step() const { return dt; }
  /// This rank's particles (owned ones and ghosts; all of them on one rank).
  const ParticleStore<dim> &particles() const { return store; }
  /// The split over MPI ranks.
  const Decomposition<dim> &decomposition() const { return ranks; }
  const BackgroundGrid<dim> &grid() const { return background; }
  /**
   * Continues the run saved in @p directory/checkpoint.bin (written by a run of the same
   * parameter file); output goes on in that directory. Call before run().
   */
  void resume_from(const std::string &directory);

  /// A hash of every particle field and the time: equal states, equal sums (FNV-1a).
  std::uint64_t state_checksum();

  /// Kinetic, strain, dissipated energy, external work and total energy (J) now.
  std::map<std::string, double> energies() const;

private:
  // The stages of a step, in order.
  void initialise_accelerations();
  void locate_and_sort();
  void particles_to_grid();
  void predict_displacement_rates(double t_half);
  void update_stresses_and_forces();
  /// Accelerations with contact and constraints; returns M a where the mass matrix
  /// is not lumped (null otherwise), for the reactions.
  const std::vector<Tensor<1, dim>> *correct_accelerations();
  /// Reactions, then the Newmark corrector on the particles; returns the first
  /// particle that went wrong (or the number of particles).
  std::size_t
  update_particles(const std::vector<Tensor<1, dim>> *mass_times_acceleration);
  void abort_unstable(std::size_t p) const;
  /**
   * Stops the run on every rank if particle @p p of some rank (p = store.size(): none
   * here) went wrong, naming the lowest id; the rank holding it says why.
   */
  void stop_if_any(std::size_t p, const std::function<void(std::size_t)> &stop) const;
  /// Sets up the split over MPI ranks and keeps this rank's particles.
  void distribute();
  /// Where this rank's checkpoint goes in @p directory.
  std::string checkpoint_file(const std::string &directory) const;
  /// Distributed runs: each rank's particles, ghosts and exchange time.
  void report_balance(double wall) const;
  /// The particles the output reads: all of them, on rank 0 of a distributed run.
  const ParticleStore<dim> &observed() const;
  /// True on the rank that writes history.csv and summary.json.
  bool writes_output() const { return ranks.rank() == 0; }
  /// What the scene sees of the run now.
  SceneState<dim> scene_state() const;
  /// Half-width of the central difference that gives prescribed accelerations.
  double derivative_step() const { return 1e-3 * dt; }

  // Set-up.
  void setup_particles(ParameterHandler &prm, const ParameterCounts &counts);
  /// The particle and grid file series in @p directory.
  void setup_output(const std::string &directory);

  // The run loop and its output.
  void prepare_output();
  void advance_to_end(TimerOutput &timer, std::chrono::steady_clock::time_point start);
  void write_output_row();
  void write_checkpoint();
  void serialize(Archive &ar);
  void report_progress(std::chrono::steady_clock::time_point start);
  RunSummary summarise(double wall);
  void abort_run(std::size_t p, const std::string &why) const;

  std::ostream &console_stream;
  ConditionalOStream pcout;
  RunParameters<dim> parameters;
  std::unique_ptr<Scene<dim>> scene;
  Decomposition<dim> ranks;
  /// Every rank's particles, gathered on rank 0 for output (distributed runs).
  mutable ParticleStore<dim> gathered;
  /// Particles in the whole run (on all ranks).
  std::size_t n_particles = 0;
  /// True once this rank keeps only its own particles and ghosts.
  bool particles_split = false;
  /// Their total mass at the start (kg).
  double initial_mass = 0;
  std::string output_directory;

  BackgroundGrid<dim> background;
  ParticleStore<dim> store;
  MaterialSet<dim> materials;
  FractureCoupling<dim> fracture;
  CrackSet<dim> cracks;
  std::unique_ptr<ShapeFunction<dim>> shape_function;
  NodeConstraints<dim> constraints;
  GridTransfer<dim> transfer;
  CrackFaceContact<dim> crack_contact;
  BodyContact<dim> contact;
  /// Work the prescribed bodies did on the others in the current step.
  double contact_work = 0;

  /// Wall time per stage of a step (the table at the end of a run, and summary.json).
  StageTimer stages;
  struct StageIds
  {
    unsigned int crack_growth, locate, to_grid, rates, stresses_and_forces, stresses,
        fracture, forces, accelerations, to_particles, contact, exchange;
  } stage{};

  ExplicitNewmark newmark;
  double dt = 0, t = 0;
  unsigned int n_steps = 0, step_count = 0;
  double mass_tolerance = 0;
  /// a^0 = M^-1 f(u^0) is on the particles (computed, or read from a checkpoint).
  bool accelerations_initialised = false;
  // Farthest a support reaches (for the cracks' second fields) and the smallest
  // particle spacing of the bodies (for their growth).
  double crack_reach = 0, particle_spacing = std::numeric_limits<double>::max();
  /// Per body: the particles' positions and volume shares within a cell (for the
  /// crack band's width)
  std::vector<CellPlacement> body_placements;

  EnergyBalance<dim> energy;
  PeakForce<dim> peak_force;
  Probes<dim> probes;
  ExactSolution<dim> exact;
  std::unique_ptr<ParticleOutput<dim>> particle_output;
  std::unique_ptr<GridOutput<dim>> grid_output;
  HistoryFile history;
  double next_output_time            = 0;
  bool resumed                       = false;
  std::uint64_t resumed_history_size = 0;
  std::map<std::string, double> results;
  /// Why the scene ended the run before the end time (empty if it did not).
  std::string stop_reason;
};
} // namespace lme_mpm

#endif
