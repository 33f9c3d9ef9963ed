#ifndef LME_MPM_SOLVER_MASS_SOLVE_H
#define LME_MPM_SOLVER_MASS_SOLVE_H

#include <deal.II/base/tensor.h>

#include <lme_mpm/base/dealii.h>
#include <lme_mpm/solver/grid_transfer.h>
#include <lme_mpm/solver/mass_matrix.h>
#include <lme_mpm/solver/run_parameters.h>

#include <cstddef>
#include <functional>
#include <map>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace lme_mpm
{
/**
 * The mass matrix of a step's two grid solves (the predictor's rates, the
 * corrector's accelerations), as `Time/Mass matrix` chooses it: the lumped mass, whose
 * solution the caller has already, with `Mass matrix corrections` Jacobi corrections
 * towards the consistent mass M_C = sum_p m_p N_Ip N_Jp; or M_C itself, assembled once
 * per step (ConsistentMassMatrix, Trilinos) and solved by conjugate gradients
 * preconditioned with the lumped mass, on one rank or several. Each solve starts from
 * the lumped solution (the last step's solution was measured as a start and takes
 * three times the iterations, doc/shape_functions.md), and ends keeping a free body's
 * momentum to round-off. Counts the solves' iterations for
 * history.csv and summary.json (doc/shape_functions.md).
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
  /// Distributed runs: the ranks' node ownership and communicator.
  void set_ranks(const RankReductions &ranks, MPI_Comm comm)
  {
    matrix.set_ranks(ranks, comm);
  }
  /// M_C of this step from the connectivity of @p transfer (after the particle-to-grid
  /// pass) and the masses of @p particles; nothing unless M_C is solved.
  void assemble(const GridTransfer<dim> &transfer, const ParticleStore<dim> &particles);

  /**
   * Turns the lumped solution in @p x (constraints imposed) into the run's: corrected,
   * or solved with M_C on the active fields with more than @p mass_tolerance mass.
   * Components that @p constrain sets keep their values; it must act node by node,
   * setting values that do not depend on the rest of its argument or projecting it
   * affinely (the constraints and prescribed bodies do). Throws, naming @p what and @p t,
   * if a solve does not reach its tolerance (the run stops with its output kept).
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
  unsigned int conjugate_gradients(const NodalFields<dim> &fields,
                                   std::vector<Tensor<1, dim>> &x,
                                   const std::vector<Tensor<1, dim>> &rhs,
                                   double mass_tolerance, const Constrain &constrain);

  /// The constraints' values (g) and linear part (projected), node by node.
  void read_constraints(const NodalFields<dim> &fields, double mass_tolerance,
                        const Constrain &constrain);
  /// Restores the momentum of unconstrained fields after a solve (see the .cc).
  void keep_momentum(const NodalFields<dim> &fields, std::vector<Tensor<1, dim>> &x,
                     const std::vector<Tensor<1, dim>> &rhs, double mass_tolerance) const;

  const RunParameters<dim> &run;
  ConsistentMassMatrix<dim> matrix;
  /// Residual, preconditioned residual, direction, M_C times the direction, and the
  /// constraints' own values.
  std::vector<Tensor<1, dim>> r, z, p, q, g;
  /// The fields a solve holds apart, with the linear part of their constraints.
  std::vector<std::pair<unsigned int, Tensor<2, dim>>> projected;
  std::size_t solves = 0, iterations = 0;
  /// The counts at the last history row (the output reads the parts as const).
  mutable std::size_t row_solves = 0, row_iterations = 0;
  unsigned int most = 0;
};
} // namespace lme_mpm

#endif
