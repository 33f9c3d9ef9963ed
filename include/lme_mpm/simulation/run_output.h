#ifndef LME_MPM_SIMULATION_RUN_OUTPUT_H
#define LME_MPM_SIMULATION_RUN_OUTPUT_H

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>

#include <lme_mpm/base/archive.h>
#include <lme_mpm/base/stage_timer.h>
#include <lme_mpm/output/energy_balance.h>
#include <lme_mpm/output/exact_solution.h>
#include <lme_mpm/output/fast_particles.h>
#include <lme_mpm/output/force_means.h>
#include <lme_mpm/output/grid_output.h>
#include <lme_mpm/output/history_file.h>
#include <lme_mpm/output/load_test.h>
#include <lme_mpm/output/particle_output.h>
#include <lme_mpm/output/peak_force.h>
#include <lme_mpm/output/probes.h>
#include <lme_mpm/output/run_summary.h>
#include <lme_mpm/simulation/parts.h>
#include <lme_mpm/solver/time_step_control.h>

#include <algorithm>
#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace lme_mpm
{
/**
 * What a run writes: history.csv (one row per output time), the particle and grid
 * files, summary.json, damage.csv and the other end-of-run files, and the console.
 * Reads the parts (SimulationParts) and never changes them; a distributed run's rows
 * read every particle, gathered on rank 0, which writes the files.
 *
 * The history columns and the summary values come from one list of writers, each a
 * part's columns with its results: the energies, the constraint sets (and the peak
 * force), the bodies (and their contact forces), the probes, the scene and the exact
 * solution. A part that reports adds itself to that list once.
 */
template <int dim>
class RunOutput
{
public:
  RunOutput(const SimulationParts<dim> &parts, const StageTimer &stages,
            std::ostream &console);

  /// Declares the output's own parts: probes and verification.
  static void declare_parameters(ParameterHandler &prm, unsigned int n_probes);
  /// Reads them, the peak-force set, and opens the files of Output/Directory.
  void parse_parameters(ParameterHandler &prm, unsigned int n_probes);
  /// Output goes to @p directory from now on (a resumed run's).
  void open(const std::string &directory);
  /// How the run was started: prepare() writes its parameters as parameters.prm and
  /// summarise() hands it to summary.json.
  void keep_record(RunRecord r) { record = std::move(r); }
  /**
   * The parameters into a checkpoint; when loading, refuses (ExcBadInput naming the
   * entry) a run whose parameters differ from the checkpoint's in an entry that
   * changes results.
   */
  void serialize_parameters(Archive &ar);
  const std::string &directory() const { return output_directory; }
  /// Console output: on rank 0 at a verbosity above 0.
  ConditionalOStream &console() { return pcout; }

  /**
   * Records the run's particles at the start, before they are distributed over the
   * ranks: their number, mass, each body's volume (initial_volume_<body>) and the
   * largest free body's diagonal, which the fast-particle measure reads.
   */
  void record_totals();
  /**
   * Before the first step: the exact solution's norms, the directory (nothing is
   * written before this), history.csv's header (or its continuation after a
   * checkpoint with @p resumed), and the run's banner.
   */
  void prepare(bool resumed, const TimeStepControl &clock);
  /**
   * After each step of length @p dt, which ended at time @p t: its external work, the
   * energy drift, the peak force, the contact forces' means, the fastest particle's
   * speed @p max_speed (FastParticles), and the scene's own tracking and stop rule
   * (stopping() tells whether it asked to end the run).
   */
  void after_step(double external_work, double dt, double t, double max_speed);
  /// The first history row of a run (not of a resumed one), at step 0.
  void write_first_row(double t);
  /// True once @p t has reached the next output time of the history or of a file
  /// series (within half a step @p dt).
  bool due(const double t, const double dt) const
  {
    return t >= std::min({next_time, next_particle_time, next_grid_time}) - 0.5 * dt;
  }
  /**
   * At step @p step, time @p t: the history row and the particle and grid files that
   * are due; the next output times are the first multiples of their intervals past
   * t (with the step @p dt).
   */
  void write_due_row(unsigned int step, double t, double dt);
  /// The end of a run at step @p step, time @p t: a history row and particle and
  /// grid files (where on), those that write_due_row() has not written at this step.
  void write_final(unsigned int step, double t);
  /// True once the scene's stop rule has ended the run (after_step()).
  bool stopping() const { return !scene_stop.empty(); }
  /// Why the scene ended the run (empty if it did not).
  const std::string &stop_reason() const { return scene_stop; }

  /// The largest drift of the total energy so far (EnergyBalance; rank 0's).
  double energy_drift() const { return energy.max_drift(); }
  /// The energies now (J), over every particle of every rank.
  std::map<std::string, double> energies() const;
  /// The values of summary.json, from every particle; the files of the end of a run
  /// (one that cannot be written is skipped, and named by failed_end_file()).
  RunSummary summarise(double wall, unsigned int steps, const TimeStepControl &clock,
                       double t);
  /// Why an end-of-run file could not be written in summarise() (empty: none).
  const std::string &failed_end_file() const { return end_file_failure; }
  /// The progress line after @p step steps, a fraction @p done of the run.
  void report_progress(std::chrono::steady_clock::time_point start, unsigned int step,
                       double done, double t);
  /// The stage table, each rank's share (distributed runs, with its
  /// @p exchange_seconds) and the closing line.
  void report_end(double wall, unsigned int steps, double exchange_seconds);

  /// What the scene sees of the run in a history row or at its end, at @p t, with
  /// the particles @p particles (every particle, on rank 0).
  SceneState<dim> scene_state(double t, const ParticleStore<dim> &particles) const;
  /// What the scene sees after a step of length @p dt that ended at @p t (this
  /// rank's particles).
  SceneState<dim> step_state(double t, double dt) const;
  /// The particles the output reads: all of them (gathered on rank 0 of a
  /// distributed run, empty elsewhere).
  const ParticleStore<dim> &observed() const;
  /// The particles the last observed() returned, without gathering them again.
  const ParticleStore<dim> &last_observed() const
  {
    return parts.ranks.distributed() ? gathered : parts.particles;
  }
  bool writes_files() const { return parts.ranks.rank() == 0; }

  void serialize(Archive &ar);

private:
  RunRecord record;
  /// One part's history columns and summary values.
  struct Columns
  {
    std::function<void(std::ostream &)> header;
    std::function<void(std::ostream &, const ParticleStore<dim> &, double)> row;
    std::function<void(std::map<std::string, double> &, const ParticleStore<dim> &,
                       double)>
        results;
  };
  void add_columns();
  /// A history row, a particle file and a grid file, as asked.
  void write_outputs(unsigned int step, double t, bool row, bool particles, bool grid);
  /// The steps of the last history row, particle file and grid file.
  unsigned int row_step = 0, particle_step = 0, grid_step = 0;
  bool any_row = false, any_particle_file = false, any_grid_file = false;
  /// The nodal masses and rates summed over their owners (distributed grid files).
  void write_grid_file(double t);

  const SimulationParts<dim> &parts;
  const StageTimer &stages;
  ConditionalOStream pcout;
  std::string output_directory;
  std::vector<Columns> columns;
  /// Every rank's particles, gathered on rank 0 for output (distributed runs).
  mutable ParticleStore<dim> gathered;
  std::size_t n_particles = 0;
  double initial_mass     = 0;
  std::vector<std::pair<std::string, double>> body_volumes;

  EnergyBalance<dim> energy;
  PeakForce<dim> peak_force;
  LoadTest load_test;
  /// The bodies' contact forces, averaged over each output interval.
  ForceMeans<dim> contact_means;
  /// The contact force each body received in the last step: multi-field contact's
  /// and the rigid surfaces'.
  const std::vector<Tensor<1, dim>> &body_forces();
  std::vector<Tensor<1, dim>> force_sum;
  Probes<dim> probes;
  FastParticles fast_particles;
  ExactSolution<dim> exact;
  std::unique_ptr<ParticleOutput<dim>> particle_output;
  std::unique_ptr<GridOutput<dim>> grid_output;
  HistoryFile history;
  /// The next times of a history row, a particle file and a grid file.
  double next_time = 0, next_particle_time = 0, next_grid_time = 0;
  /// The interval of the series that writes when @p next is due (a huge one for a
  /// series that is off).
  double file_interval(bool on, double interval) const;
  std::uint64_t resumed_history_size = 0;
  std::map<std::string, double> results;
  std::string scene_stop;
  std::string end_file_failure;
  /// Distributed runs: each rank's particles, ghosts and @p exchange_seconds.
  void report_balance(double wall, double exchange_seconds);
};
} // namespace lme_mpm

#endif
