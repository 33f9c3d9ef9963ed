#include <lme_mpm/base/input.h>
#include <lme_mpm/solver/mass_solve.h>

#include <algorithm>
#include <sstream>

namespace lme_mpm
{
template <int dim>
void MassSolve<dim>::require_one_rank() const
{
  AssertThrow(!run.consistent_mass,
              ExcBadInput("Time/Mass matrix",
                          "'consistent' runs on one MPI rank (each rank's halo holds "
                          "what a fixed number of grid transfers reads, and a solve to a "
                          "tolerance reaches the whole grid); use 'lumped' with 'Mass "
                          "matrix corrections' on several ranks"));
}

template <int dim>
void MassSolve<dim>::solve(GridTransfer<dim> &transfer, std::vector<Tensor<1, dim>> &x,
                           const std::vector<Tensor<1, dim>> &rhs,
                           const double mass_tolerance, const Constrain &constrain,
                           const char *what, const double t)
{
  if (!run.consistent_mass)
  {
    if (run.mass_corrections > 0)
      transfer.correct_towards_consistent_mass(x, rhs, run.mass_corrections,
                                               mass_tolerance, constrain);
    return;
  }
  const unsigned int it =
      conjugate_gradients(transfer, x, rhs, mass_tolerance, constrain);
  if (it > run.consistent_mass_iterations)
  {
    std::ostringstream msg;
    msg << "The consistent-mass solve of the " << what << " at time " << t
        << " s did not reach 'Time/Consistent mass tolerance' = "
        << run.consistent_mass_tolerance << " within 'Time/Consistent mass iterations' = "
        << run.consistent_mass_iterations
        << ": the consistent mass matrix is singular or nearly so where a body's field "
           "has fewer particles than nodes (wide supports, few particles per cell); "
           "use 'Time/Mass matrix = lumped' (with 'Mass matrix corrections'), more "
           "particles per cell, or a looser tolerance";
    AssertThrow(false, ExcMessage(msg.str()));
  }
  ++solves;
  iterations += it;
  most = std::max(most, it);
}

template <int dim>
unsigned int MassSolve<dim>::conjugate_gradients(GridTransfer<dim> &transfer,
                                                 std::vector<Tensor<1, dim>> &x,
                                                 const std::vector<Tensor<1, dim>> &rhs,
                                                 const double mass_tolerance,
                                                 const Constrain &constrain)
{
  const NodalFields<dim> &fields          = transfer.nodes();
  const std::vector<unsigned int> &active = fields.active;
  const std::vector<double> &mass         = fields.mass;
  for (auto *v : {&r, &z, &p, &q, &g})
    if (v->size() < x.size())
      v->resize(x.size());
  // The constraints' own values: what they write on a zero vector. A vector less
  // them is zero on the constrained components and unchanged elsewhere, so the
  // residuals and directions stay off those components (and off light nodes).
  for (const unsigned int I : active)
    g[I] = Tensor<1, dim>();
  constrain(g);
  const auto project = [&](std::vector<Tensor<1, dim>> &v)
  {
    constrain(v);
    for (const unsigned int I : active)
      v[I] = mass[I] > mass_tolerance ? v[I] - g[I] : Tensor<1, dim>();
  };
  // Norms weighted by the inverse lumped mass; the sums run over the active fields in
  // order, so the result does not depend on the thread count.
  const auto precondition = [&](const unsigned int I)
  { return mass[I] > mass_tolerance ? r[I] / mass[I] : Tensor<1, dim>(); };
  for (const unsigned int I : active)
    p[I] = rhs[I];
  project(p);
  double b2 = 0;
  for (const unsigned int I : active)
    if (mass[I] > mass_tolerance)
      b2 += p[I] * p[I] / mass[I];
  transfer.apply_consistent_mass(x, q);
  for (const unsigned int I : active)
    r[I] = rhs[I] - q[I];
  project(r);
  double rz = 0;
  for (const unsigned int I : active)
    z[I] = precondition(I), p[I] = z[I], rz += r[I] * z[I];
  const double goal = run.consistent_mass_tolerance * run.consistent_mass_tolerance * b2;
  for (unsigned int it = 0; rz > goal; ++it)
  {
    if (it == run.consistent_mass_iterations)
      return it + 1;
    transfer.apply_consistent_mass(p, q);
    project(q);
    double pq = 0;
    for (const unsigned int I : active)
      pq += p[I] * q[I];
    // M_C is only semi-definite where a field has fewer particles than nodes.
    if (!(pq > 0))
      return run.consistent_mass_iterations + 1;
    const double alpha = rz / pq;
    double rz_new      = 0;
    for (const unsigned int I : active)
    {
      x[I] += alpha * p[I];
      r[I] -= alpha * q[I];
      z[I] = precondition(I);
      rz_new += r[I] * z[I];
    }
    for (const unsigned int I : active)
      p[I] = z[I] + (rz_new / rz) * p[I];
    rz = rz_new;
    if (rz <= goal)
      return it + 1;
  }
  return 0;
}

template <int dim>
void MassSolve<dim>::write_header(std::ostream &out) const
{
  if (run.consistent_mass)
    out << ",mass_solve_iterations";
}

template <int dim>
void MassSolve<dim>::write_row(std::ostream &out) const
{
  if (!run.consistent_mass)
    return;
  const std::size_t n = solves - row_solves, its = iterations - row_iterations;
  out << "," << (n > 0 ? double(its) / n : 0.0);
  row_solves = solves, row_iterations = iterations;
}

template <int dim>
void MassSolve<dim>::add_results(std::map<std::string, double> &results) const
{
  if (!run.consistent_mass)
    return;
  results["mass_solve_mean_iterations"] = solves > 0 ? double(iterations) / solves : 0.0;
  results["mass_solve_max_iterations"]  = most;
}

template class MassSolve<2>;
template class MassSolve<3>;
} // namespace lme_mpm
