#ifndef LME_MPM_OUTPUT_RUN_SUMMARY_H
#define LME_MPM_OUTPUT_RUN_SUMMARY_H

#include <deal.II/base/point.h>

#include <lme_mpm/base/run_record.h>
#include <lme_mpm/particles/particle_store.h>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace lme_mpm
{
/// What summary.json reports: how the run ended and its values by name.
struct RunSummary
{
  /**
   * How the run ended: "completed" (reached its end time), "stopped" (ended on purpose
   * before it: @p stop_reason says by what), "aborted" (unstable or failed, output
   * kept) or "interrupted" (SIGINT / SIGTERM). README.md gives each one's exit code.
   */
  std::string status = "completed";
  /// For "stopped": "scene" (the scene's own stop rule) or "Time/Maximum steps".
  std::string stop_reason;
  std::string message;
  std::map<std::string, double> values;
  /**
   * What the user should know about results that ran to their end (an entry outside
   * its physical range, particles crossing cells fast on linear or uGIMP functions):
   * summary.json's "warnings" list, one sentence each, printed on the console too.
   */
  std::vector<std::string> warnings;
  /// How the run was started (summary.json's "run" object).
  RunRecord record;

  /// Writes summary.json; @p checksum is the final state's (Simulation::state_checksum).
  void write(const std::string &file, const std::string &shape_function,
             std::uint64_t checksum, unsigned int dim) const;
};

/// The failed particles as a point set (failed_particles.csv) for scripts without a
/// VTU reader: id, current and reference position, damage.
template <int dim>
void write_failed_particles(const std::string &file, const ParticleStore<dim> &particles);

/// The final damage field of every particle (damage.csv) for plotting scripts: id,
/// body, current and reference position, damage (1 for failed particles).
template <int dim>
void write_damage_field(const std::string &file, const ParticleStore<dim> &particles);

/// Polylines (cracks.csv): one row per point, 'crack,point,x0,x1'.
template <int dim>
void write_polylines(const std::string &file,
                     const std::vector<std::vector<Point<dim>>> &lines);
} // namespace lme_mpm

#endif
