#ifndef LME_MPM_SOLVER_MASS_SOLVE_H
#define LME_MPM_SOLVER_MASS_SOLVE_H

#include <deal.II/base/tensor.h>

#include <lme_mpm/base/dealii.h>
#include <lme_mpm/solver/grid_transfer.h>
#include <lme_mpm/solver/run_parameters.h>

#include <cstddef>
#include <functional>
#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace lme_mpm
{
/**
 * The mass matrix of a step's two grid solves (the predictor's rates, the
 * corrector's accelerations), as `Time/Mass matrix` chooses it: the lumped mass, whose
 * solution the caller has already, with `Mass matrix corrections` Jacobi corrections
 * towards the consistent mass M_C = sum_p m_p N_Ip N_Jp; or M_C itself, solved by
 * conjugate gradients preconditioned with the lumped mass and started from the lumped
 * solution. Each product M_C v is the pair of transfers of
 * GridTransfer::apply_consistent_mass(), so no matrix is stored. Counts the solves'
 * iterations for history.csv and summary.json (doc/shape_functions.md).
 */
template <int dim>
class MassSolve
{
public:
  /// Re-imposes the constraints on a nodal vector.
  using Constrain = std::function<void(std::vector<Tensor<1, dim>> &)>;

  /// Reads its choice from @p run when it acts (the entries are parsed later).
  explicit MassSolve(const RunParameters<dim> &run) : run(run) {}

  /// Whether the solves differ from the lumped one (corrections or M_C).
  bool active() const { return run.consistent_mass || run.mass_corrections > 0; }
  /// Whether M_C itself is solved.
  bool consistent() const { return run.consistent_mass; }
  /// For a run on several ranks: throws ExcBadInput naming 'Time/Mass matrix' if it
  /// asks for M_C (a rank's halo holds what a fixed number of transfers reads).
  void require_one_rank() const;

  /**
   * Turns the lumped solution in @p x (constraints imposed) into the run's: corrected,
   * or solved with M_C on the active fields with more than @p mass_tolerance mass.
   * Components that @p constrain sets keep their values; it must set values that do
   * not depend on the rest of its argument, or project it affinely (the constraints
   * and prescribed bodies do). Throws, naming @p what and @p t, if a solve does not
   * reach its tolerance (the run stops with its output kept).
   */
  void solve(GridTransfer<dim> &transfer, std::vector<Tensor<1, dim>> &x,
             const std::vector<Tensor<1, dim>> &rhs, double mass_tolerance,
             const Constrain &constrain, const char *what, double t);

  /// history.csv: the mean iterations per solve since the last row (M_C only).
  void write_header(std::ostream &out) const;
  void write_row(std::ostream &out) const;
  /// summary.json: the mean and largest iterations per solve (M_C only).
  void add_results(std::map<std::string, double> &r) const;

private:
  /// The conjugate-gradient iterations taken, or max + 1 if the tolerance was missed.
  unsigned int conjugate_gradients(GridTransfer<dim> &transfer,
                                   std::vector<Tensor<1, dim>> &x,
                                   const std::vector<Tensor<1, dim>> &rhs,
                                   double mass_tolerance, const Constrain &constrain);

  const RunParameters<dim> &run;
  /// Residual, preconditioned residual, direction, M_C times the direction, and the
  /// constraints' own values.
  std::vector<Tensor<1, dim>> r, z, p, q, g;
  std::size_t solves = 0, iterations = 0;
  /// The counts at the last history row (the output reads the parts as const).
  mutable std::size_t row_solves = 0, row_iterations = 0;
  unsigned int most = 0;
};
} // namespace lme_mpm

#endif
