#ifndef LME_MPM_SIMULATION_RUN_GUARD_H
#define LME_MPM_SIMULATION_RUN_GUARD_H

#include <deal.II/base/exceptions.h>

#include <lme_mpm/distributed/decomposition.h>
#include <lme_mpm/grid/background_grid.h>
#include <lme_mpm/particles/particle_store.h>

#include <cstddef>
#include <functional>
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
 * A particle of some rank went wrong: every rank of a distributed run stops with the
 * diagnostic (@p arg1) of the rank that holds it.
 */
DeclException1(ExcRunStopped, std::string, << arg1);
/// SIGINT or SIGTERM arrived (@p arg1 its name): the run ends after the step.
DeclException3(ExcInterrupted, std::string, unsigned int, double,
               << "Interrupted by " << arg1 << " after step " << arg2 << ", time " << arg3
               << " s");
/**
 * The run ended before its end time with its output written (@p arg1 says why). On
 * several ranks every rank throws it together, unlike an error on one rank.
 */
DeclException1(ExcRunFailed, std::string, << arg1);
/// The run ended on SIGINT or SIGTERM, its output written (@p arg1 says what is left).
DeclException1(ExcRunInterrupted, std::string, << arg1);

/**
 * Stops the run, on every rank together, when a particle goes wrong: it left the
 * grid, or the step made it unstable (non-finite velocity, inverted material, a move
 * of more than half a cell). The diagnostic names the step, the time, the particle
 * (the lowest id over the ranks, so every run reports the same one) and the likely
 * cause; the rank holding the particle words it.
 */
template <int dim>
class RunGuard
{
public:
  RunGuard(const ParticleStore<dim> &particles, const BackgroundGrid<dim> &grid,
           const Decomposition<dim> &ranks)
      : particles(particles), grid(grid), ranks(ranks)
  {
  }

  /// Stops if particle @p p (p = particles.size(): none) left the grid at step
  /// @p step, time @p t, found by the search of cells. The step before has checked
  /// every owned particle against the grid (stop_if_unstable()), so this happens
  /// only to a particle that started outside it: the check is this rank's alone.
  void stop_if_lost(std::size_t p, unsigned int step, double t) const;
  /// Stops if particle @p p of some rank went wrong (or left the grid) in the step
  /// that ended at step @p step, time @p t. @p on_some_rank: whether any rank has
  /// such a particle, reduced by the caller with the step's other maxima; only then
  /// do the ranks agree on which particle to name.
  void stop_if_unstable(std::size_t p, bool on_some_rank, unsigned int step,
                        double t) const;
  /**
   * Stops the run (on every rank) once the total energy has drifted by more than
   * half of the run's energy scale (EnergyBalance): no stable run does that. Acts once
   * the travel limit on the time step has bound (@p limited_steps > 0), which would
   * otherwise carry a run that blew up onwards at ever shorter steps without any
   * particle moving half a cell in one.
   */
  void stop_if_energy_runs_away(double drift, unsigned int limited_steps,
                                unsigned int step, double t) const;
  /// Throws ExcInterrupted for @p signal, the largest signal number any rank has
  /// received (interrupt.h; 0: none), reduced by the caller with the step's other
  /// maxima, so that every rank stops at the same step.
  void stop_if_interrupted(int signal, unsigned int step, double t) const;

private:
  /// Throws ExcRunAborted for particle @p p (one rank) or ExcRunStopped with its
  /// holder's message (several), with the reason @p why(p).
  void stop_if_any(std::size_t p, unsigned int step, double t,
                   const std::function<std::string(std::size_t)> &why) const;

  const ParticleStore<dim> &particles;
  const BackgroundGrid<dim> &grid;
  const Decomposition<dim> &ranks;
};
} // namespace lme_mpm

#endif
