#include <lme_mpm/base/input.h>
#include <lme_mpm/solver/mass_solve.h>

#include <deal.II/base/symmetric_tensor.h>

#include <algorithm>
#include <sstream>

namespace lme_mpm
{
template <int dim>
void MassSolve<dim>::assemble(const GridTransfer<dim> &transfer,
                              const ParticleStore<dim> &particles)
{
  if (run.consistent_mass)
    matrix.assemble(transfer.connectivity(), particles.mass, transfer.nodes().layout,
                    transfer.nodes().active);
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
      conjugate_gradients(transfer.nodes(), x, rhs, mass_tolerance, constrain);
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
    AssertThrow(false, ExcStepFailedOnAllRanks(msg.str()));
  }
  matrix.distribute(x);
  ++solves;
  iterations += it;
  most = std::max(most, it);
}

template <int dim>
void MassSolve<dim>::read_constraints(const NodalFields<dim> &fields,
                                      const double mass_tolerance,
                                      const Constrain &constrain)
{
  const std::vector<unsigned int> &active = fields.active;
  const std::vector<unsigned int> &rows   = matrix.rows();
  const std::vector<double> &mass         = fields.mass;
  // The constraints' own values: what they write on a zero vector. A vector less
  // them is what their linear part makes of it (zero on a fixed component, the
  // tangential part on a slip plane), so the residuals and directions stay off the
  // constrained components. That part is read node by node once per solve, from
  // what the constraints make of the unit vectors: evaluating the constraints'
  // functions in every iteration would cost more than the products.
  for (const unsigned int I : active)
    g[I] = Tensor<1, dim>();
  constrain(g);
  projected.clear();
  {
    std::vector<Tensor<2, dim>> A(rows.size());
    for (unsigned int d = 0; d < dim; ++d)
    {
      for (const unsigned int I : active)
        q[I] = Tensor<1, dim>(), q[I][d] = 1;
      constrain(q);
      for (std::size_t k = 0; k < rows.size(); ++k)
        for (unsigned int e = 0; e < dim; ++e)
          A[k][e][d] = q[rows[k]][e] - g[rows[k]][e];
    }
    const Tensor<2, dim> identity(unit_symmetric_tensor<dim>());
    for (std::size_t k = 0; k < rows.size(); ++k)
    {
      const unsigned int I = rows[k];
      if (!(mass[I] > mass_tolerance))
        projected.emplace_back(I, Tensor<2, dim>());
      else if (A[k] != identity)
        projected.emplace_back(I, A[k]);
    }
  }
}

template <int dim>
unsigned int MassSolve<dim>::conjugate_gradients(const NodalFields<dim> &fields,
                                                 std::vector<Tensor<1, dim>> &x,
                                                 const std::vector<Tensor<1, dim>> &rhs,
                                                 const double mass_tolerance,
                                                 const Constrain &constrain)
{
  const std::vector<unsigned int> &rows = matrix.rows();
  const std::vector<double> &mass       = fields.mass;
  for (auto *v : {&r, &z, &p, &q, &g})
    if (v->size() < x.size())
      v->resize(x.size());
  read_constraints(fields, mass_tolerance, constrain);
  const auto project = [&](std::vector<Tensor<1, dim>> &v)
  {
    for (const auto &[I, A] : projected)
      v[I] = A * v[I];
  };
  const auto inverse_mass = [&](const unsigned int I)
  { return mass[I] > mass_tolerance ? 1.0 / mass[I] : 0.0; };
  // Norms weighted by the inverse lumped mass; the sums run over this rank's rows
  // in order, then over the ranks, so they do not depend on the thread count.
  const auto residual = [&]()
  {
    matrix.vmult(x, q);
    for (const unsigned int I : rows)
      r[I] = rhs[I] - q[I];
    project(r);
  };
  for (const unsigned int I : rows)
    p[I] = rhs[I];
  project(p);
  double b2 = 0;
  for (const unsigned int I : rows)
    b2 += p[I] * p[I] * inverse_mass(I);
  b2 = matrix.sum(b2);
  constrain(x);
  residual();
  double rz = 0;
  for (const unsigned int I : rows)
    z[I] = inverse_mass(I) * r[I], p[I] = z[I], rz += r[I] * z[I];
  rz                = matrix.sum(rz);
  const double goal = run.consistent_mass_tolerance * run.consistent_mass_tolerance * b2;
  unsigned int it   = 0;
  for (; rz > goal; ++it)
  {
    if (it == run.consistent_mass_iterations)
      return it + 1;
    matrix.vmult(p, q);
    project(q);
    double pq = 0;
    for (const unsigned int I : rows)
      pq += p[I] * q[I];
    pq = matrix.sum(pq);
    // M_C is only semi-definite where a field has fewer particles than nodes.
    if (!(pq > 0))
      return run.consistent_mass_iterations + 1;
    const double alpha = rz / pq;
    double rz_new      = 0;
    for (const unsigned int I : rows)
    {
      x[I] += alpha * p[I];
      r[I] -= alpha * q[I];
      z[I] = inverse_mass(I) * r[I];
      rz_new += r[I] * z[I];
    }
    rz_new = matrix.sum(rz_new);
    for (const unsigned int I : rows)
      p[I] = z[I] + (rz_new / rz) * p[I];
    rz = rz_new;
  }
  keep_momentum(fields, x, rhs, mass_tolerance);
  return it;
}

template <int dim>
void MassSolve<dim>::keep_momentum(const NodalFields<dim> &fields,
                                   std::vector<Tensor<1, dim>> &x,
                                   const std::vector<Tensor<1, dim>> &rhs,
                                   const double mass_tolerance) const
{
  // Where nothing holds the fields, sum_I m_I x_I = sum_I b_I: the momentum the
  // particles gain is the total force. Conjugate gradients preconditioned with the
  // lumped mass keep this in exact arithmetic (1^T M_C = m_L^T), but the round-off
  // of each iteration grows with the next ones; the uniform velocity that restores
  // it is added to the fields the solve moved.
  for (const auto &held : projected)
    if (held.second != Tensor<2, dim>())
      return;
  const std::vector<unsigned int> &rows = matrix.rows();
  std::vector<double> sums(2 * dim + 1, 0.0);
  for (const unsigned int I : rows)
  {
    for (unsigned int d = 0; d < dim; ++d)
      sums[d] += rhs[I][d] - fields.mass[I] * x[I][d];
    if (fields.mass[I] > mass_tolerance)
      sums[2 * dim] += fields.mass[I];
  }
  matrix.sum(sums);
  if (!(sums[2 * dim] > 0))
    return;
  Tensor<1, dim> shift;
  for (unsigned int d = 0; d < dim; ++d)
    shift[d] = sums[d] / sums[2 * dim];
  for (const unsigned int I : rows)
    if (fields.mass[I] > mass_tolerance)
      x[I] += shift;
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
