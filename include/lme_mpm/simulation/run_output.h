#ifndef LME_MPM_SIMULATION_RUN_OUTPUT_H
#define LME_MPM_SIMULATION_RUN_OUTPUT_H

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>

#include <lme_mpm/base/archive.h>
#include <lme_mpm/base/stage_timer.h>
#include <lme_mpm/output/energy_balance.h>
#include <lme_mpm/output/exact_solution.h>
#include <lme_mpm/output/force_means.h>
#include <lme_mpm/output/grid_output.h>
#include <lme_mpm/output/history_file.h>
#include <lme_mpm/output/particle_output.h>
#include <lme_mpm/output/peak_force.h>
#include <lme_mpm/output/probes.h>
#include <lme_mpm/output/run_summary.h>
#include <lme_mpm/simulation/parts.h>
#include <lme_mpm/solver/time_step_control.h>

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

  /// The particles of the run: @p n of them (all ranks), @p mass kg, at the start.
  void set_totals(std::size_t n, double mass)
  {
    n_particles  = n;
    initial_mass = mass;
  }
  /**
   * Before the first step: the exact solution's norms, the directory (nothing is
   * written before this), history.csv's header (or its continuation after a
   * checkpoint with @p resumed), and the run's banner.
   */
  void prepare(bool resumed, const TimeStepControl &clock);
  /// After each step of length @p dt: its external work, the peak force and the
  /// contact forces' means.
  void after_step(double external_work, double dt);
  /// The first history row of a run (not of a resumed one), at step 0.
  void write_first_row(double t);
  /// True once @p t has reached the next output time (within half a step @p dt).
  bool due(const double t, const double dt) const { return t >= next_time - 0.5 * dt; }
  /**
   * The row of step @p step at time @p t; the next output time is the first multiple
   * of the interval past t (with the step @p dt).
   */
  void write_due_row(unsigned int step, double t, double dt);
  /// A history row (and particle and grid files) at step @p step, time @p t.
  void write_row(unsigned int step, double t);
  /// The scene's reason to end the run after the row just written (every rank gets
  /// rank 0's answer); records it for summary.json.
  std::string scene_finished(double t);
  /// Why the scene ended the run (empty if it did not).
  const std::string &stop_reason() const { return scene_stop; }

  /// The largest drift of the total energy so far (EnergyBalance; rank 0's).
  double energy_drift() const { return energy.max_drift(); }
  /// The energies now (J), over every particle of every rank.
  std::map<std::string, double> energies() const;
  /// The values of summary.json, from every particle; the files of the end of a run.
  RunSummary summarise(double wall, unsigned int steps, const TimeStepControl &clock,
                       double t);
  /// The progress line after @p step steps, a fraction @p done of the run.
  void report_progress(std::chrono::steady_clock::time_point start, unsigned int step,
                       double done, double t);
  /// The stage table, each rank's share (distributed runs, with its
  /// @p exchange_seconds) and the closing line.
  void report_end(double wall, unsigned int steps, double exchange_seconds);

  /// What the scene sees of the run at @p t with the particles @p particles.
  SceneState<dim> scene_state(double t, const ParticleStore<dim> &particles) const;
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
  /// The step of the row being written (step 0's energy is the drift's reference).
  unsigned int row_step = 0;

  EnergyBalance<dim> energy;
  PeakForce<dim> peak_force;
  /// The bodies' contact forces, averaged over each output interval.
  ForceMeans<dim> contact_means;
  Probes<dim> probes;
  ExactSolution<dim> exact;
  std::unique_ptr<ParticleOutput<dim>> particle_output;
  std::unique_ptr<GridOutput<dim>> grid_output;
  HistoryFile history;
  double next_time                   = 0;
  std::uint64_t resumed_history_size = 0;
  std::map<std::string, double> results;
  std::string scene_stop;
  /// Distributed runs: each rank's particles, ghosts and @p exchange_seconds.
  void report_balance(double wall, double exchange_seconds);
};
} // namespace lme_mpm

#endif
