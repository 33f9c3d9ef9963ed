#ifndef LME_MPM_SOLVER_RUN_PARAMETERS_H
#define LME_MPM_SOLVER_RUN_PARAMETERS_H

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <lme_mpm/base/dealii.h>
#include <lme_mpm/base/input.h>
#include <lme_mpm/base/parameters.h>

#include <string>
#include <vector>

namespace lme_mpm
{
/// How many of each repeated subsection a parameter file declares (read first).
struct ParameterCounts
{
  unsigned int dim         = 2;
  unsigned int materials   = 1;
  unsigned int bodies      = 1;
  unsigned int constraints = 0;
  unsigned int probes      = 0;

  static void declare_parameters(ParameterHandler &prm);
  void parse_parameters(ParameterHandler &prm);

private:
  void entries(EntryList &list);
};

/**
 * The run's own entries: the problem (thickness, plane assumption, body force), time
 * stepping, output cadence and checkpoints. The parts with entries of their own
 * (grid, shape functions, materials, bodies, constraints, ...) read those themselves.
 */
template <int dim>
struct RunParameters
{
  // Problem
  double thickness  = 1;
  bool plane_stress = false;
  /// Problem/Units: "SI" or "unitless" (no physical ranges apply).
  std::string units = "SI";
  Tensor<1, dim> body_force;
  /// The body force grows linearly from zero to body_force over this time (s; 0:
  /// applied in full from the start).
  double body_force_ramp = 0;
  /// The body force at time @p t (exactly body_force once the ramp is over).
  Tensor<1, dim> body_force_at(const double t) const
  {
    return body_force_ramp > 0 && t < body_force_ramp ? body_force * (t / body_force_ramp)
                                                      : body_force;
  }
  // Time
  double end_time = 1, cfl = 0.3, fixed_time_step = 0, max_cfl = 1, newmark_gamma = 0.5;
  unsigned int mass_corrections = 0, max_steps = 0;
  /// The grid's mass matrix: the lumped one (with mass_corrections Jacobi
  /// corrections), or the consistent one solved to consistent_mass_tolerance.
  bool consistent_mass                    = false;
  double consistent_mass_tolerance        = 1e-10;
  unsigned int consistent_mass_iterations = 1000;
  /// Largest particle travel per step, in smallest cells (0: no limit).
  double particle_travel = 0;
  /// The particle update: 0 FLIP, m > 0 XPIC(m).
  unsigned int xpic_order = 0;
  // Output
  std::string directory;
  double output_interval = 0;
  /// Simulated time between particle files and between grid files (0: the history's
  /// interval).
  double particle_interval = 0, grid_interval = 0;
  /// The span of the moving means that loads are judged by (0: 10 h_min / c_P, set
  /// by the run once the wave speed is known).
  double force_window  = 0;
  bool write_particles = true, write_grid = false;
  std::string peak_force_set;
  unsigned int verbosity = 1;
  // Checkpoint
  unsigned int checkpoint_every_steps = 0;
  double checkpoint_every_seconds     = 0;

  static void declare_parameters(ParameterHandler &prm);
  /// Reads and checks the entries; throws ExcBadInput naming the entry.
  void parse_parameters(ParameterHandler &prm);

private:
  void entries(EntryList &list);
  /// The entries of the Time subsection.
  void time_entries(EntryList &list);
  std::string plane_assumption, body_force_text, particle_update, mass_matrix;
  unsigned int xpic_order_entry = 2;
};

/// The time step and the number of steps that land exactly on the end time.
struct TimeStepping
{
  double dt            = 0;
  unsigned int n_steps = 0;
};

/**
 * The time step from the CFL number or the fixed step, checked against the stability
 * limit Maximum CFL * h_min / c_P; throws ExcBadInput naming the entry, and where
 * c_P makes the step useless the entries that set it (@p wave_speed_inputs, with
 * their values, the first one blamed).
 */
template <int dim>
TimeStepping
stable_time_step(const RunParameters<dim> &run, double h_min, double max_wave_speed,
                 const std::vector<input::EntryValue> &wave_speed_inputs = {});
} // namespace lme_mpm

#endif
