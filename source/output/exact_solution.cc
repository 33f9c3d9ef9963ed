#include <lme_mpm/base/input.h>
#include <lme_mpm/output/exact_solution.h>

#include <algorithm>
#include <cmath>

namespace lme_mpm
{
template <int dim>
void ExactSolution<dim>::declare_parameters(ParameterHandler &prm)
{
  prm.enter_subsection("Verification");
  prm.declare_entry("Compare with exact solution", "false", Patterns::Bool(),
                    "Report error_displacement_l2 and error_velocity_l2 against the "
                    "exact fields below, functions of the reference position and t.");
  for (const char *s : {"Exact displacement", "Exact velocity"})
  {
    prm.enter_subsection(s);
    Functions::ParsedFunction<dim>::declare_parameters(prm, dim);
    prm.leave_subsection();
  }
  prm.declare_entry("Compare stress", "false", Patterns::Bool(),
                    "Also report error_stress_l2 against 'Exact stress' (with 'Compare "
                    "with exact solution').");
  prm.enter_subsection("Exact stress");
  Functions::ParsedFunction<dim>::declare_parameters(prm, dim * (dim + 1) / 2);
  prm.leave_subsection();
  prm.leave_subsection();
}

template <int dim>
void ExactSolution<dim>::parse_parameters(ParameterHandler &prm)
{
  prm.enter_subsection("Verification");
  if (prm.get_bool("Compare with exact solution"))
  {
    displacement = std::make_unique<Functions::ParsedFunction<dim>>(dim);
    velocity     = std::make_unique<Functions::ParsedFunction<dim>>(dim);
    input::parse_function(prm, "Exact displacement", *displacement,
                          "Verification/Exact displacement");
    input::parse_function(prm, "Exact velocity", *velocity,
                          "Verification/Exact velocity");
    if (prm.get_bool("Compare stress"))
    {
      stress = std::make_unique<Functions::ParsedFunction<dim>>(dim * (dim + 1) / 2);
      input::parse_function(prm, "Exact stress", *stress, "Verification/Exact stress");
    }
  }
  prm.leave_subsection();
}

template <int dim>
SymmetricTensor<2, dim> ExactSolution<dim>::stress_at(const Point<dim> &X) const
{
  // Components in the order xx, xy, (xz,) yy, (yz, zz).
  SymmetricTensor<2, dim> s;
  unsigned int c = 0;
  for (unsigned int i = 0; i < dim; ++i)
    for (unsigned int j = i; j < dim; ++j)
      s[i][j] = stress->value(X, c++);
  return s;
}

template <int dim>
void ExactSolution<dim>::compute_norms(const ParticleStore<dim> &store,
                                       const double end_time,
                                       const double output_interval)
{
  if (enabled())
    for (double s = 0; s <= end_time * (1 + 1e-12); s += output_interval)
    {
      displacement->set_time(s);
      velocity->set_time(s);
      double nu = 0, nv = 0;
      for (std::size_t p = 0; p < store.size(); ++p)
        for (unsigned int d = 0; d < dim; ++d)
        {
          const double u = displacement->value(store.reference_position[p], d);
          const double v = velocity->value(store.reference_position[p], d);
          nu += store.initial_volume[p] * u * u;
          nv += store.initial_volume[p] * v * v;
        }
      displacement_norm = std::max(displacement_norm, std::sqrt(nu));
      velocity_norm     = std::max(velocity_norm, std::sqrt(nv));
      if (stress)
      {
        stress->set_time(s);
        double ns = 0;
        for (std::size_t p = 0; p < store.size(); ++p)
        {
          const auto e = stress_at(store.reference_position[p]);
          ns += store.initial_volume[p] * (e * e);
        }
        stress_norm = std::max(stress_norm, std::sqrt(ns));
      }
    }
  stress_norm       = std::max(stress_norm, 1e-300);
  displacement_norm = std::max(displacement_norm, 1e-300);
  velocity_norm     = std::max(velocity_norm, 1e-300);
}

template <int dim>
void ExactSolution<dim>::write_header(std::ostream &out) const
{
  if (enabled())
    out << ",error_displacement_l2,error_velocity_l2";
  if (stress)
    out << ",error_stress_l2";
}

template <int dim>
void ExactSolution<dim>::write_row(std::ostream &out, const ParticleStore<dim> &store,
                                   const double t)
{
  if (!enabled())
    return;
  displacement->set_time(t);
  velocity->set_time(t);
  double eu = 0, ev = 0;
  for (std::size_t p = 0; p < store.size(); ++p)
  {
    const Point<dim> &X = store.reference_position[p];
    for (unsigned int d = 0; d < dim; ++d)
    {
      const double du = store.position[p][d] - X[d] - displacement->value(X, d);
      const double dv = store.velocity[p][d] - velocity->value(X, d);
      eu += store.initial_volume[p] * du * du;
      ev += store.initial_volume[p] * dv * dv;
    }
  }
  const double err_u     = std::sqrt(eu) / displacement_norm;
  const double err_v     = std::sqrt(ev) / velocity_norm;
  max_error_displacement = std::max(max_error_displacement, err_u);
  max_error_velocity     = std::max(max_error_velocity, err_v);
  out << "," << err_u << "," << err_v;
  if (stress)
  {
    stress->set_time(t);
    double es = 0;
    for (std::size_t p = 0; p < store.size(); ++p)
    {
      const auto e = store.stress[p] - stress_at(store.reference_position[p]);
      es += store.initial_volume[p] * (e * e);
    }
    const double err_s = std::sqrt(es) / stress_norm;
    max_error_stress   = std::max(max_error_stress, err_s);
    out << "," << err_s;
  }
}

template <int dim>
void ExactSolution<dim>::add_results(std::map<std::string, double> &results) const
{
  if (!enabled())
    return;
  results["max_error_displacement_l2"] = max_error_displacement;
  results["max_error_velocity_l2"]     = max_error_velocity;
  if (stress)
    results["max_error_stress_l2"] = max_error_stress;
}

template class ExactSolution<2>;
template class ExactSolution<3>;
} // namespace lme_mpm
