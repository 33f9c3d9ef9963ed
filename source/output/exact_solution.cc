#include <lme_mpm/base/input.h>
#include <lme_mpm/base/parameters.h>
#include <lme_mpm/output/exact_solution.h>

#include <algorithm>
#include <cmath>

namespace lme_mpm
{
namespace
{
/// The switches of "Verification", listed once for declaring and reading; the
/// exact fields are ParsedFunction subsections beside them.
struct VerificationEntries
{
  bool compare = false, compare_stress = false;

  void entries(EntryList &list)
  {
    list.add("Compare with exact solution", compare, "false", Patterns::Bool(),
             "Report error_displacement_l2 and error_velocity_l2 against the "
             "exact fields below, functions of the reference position and t.");
    list.add("Compare stress", compare_stress, "false", Patterns::Bool(),
             "Also report error_stress_l2 against 'Exact stress' (with 'Compare "
             "with exact solution').");
  }
};

const char *field_names[3] = {"Exact displacement", "Exact velocity", "Exact stress"};
} // namespace

template <int dim>
void ExactSolution<dim>::declare_parameters(ParameterHandler &prm)
{
  prm.enter_subsection("Verification");
  EntryList list(prm, EntryList::Mode::declare);
  VerificationEntries().entries(list);
  for (unsigned int f = 0; f < 3; ++f)
  {
    prm.enter_subsection(field_names[f]);
    Functions::ParsedFunction<dim>::declare_parameters(prm,
                                                       f < 2 ? dim : dim * (dim + 1) / 2);
    prm.leave_subsection();
  }
  prm.leave_subsection();
}

template <int dim>
void ExactSolution<dim>::parse_parameters(ParameterHandler &prm)
{
  prm.enter_subsection("Verification");
  VerificationEntries in;
  EntryList list(prm, EntryList::Mode::parse);
  in.entries(list);
  const auto parse = [&](const unsigned int f, const unsigned int n_components)
  {
    auto function = std::make_unique<Functions::ParsedFunction<dim>>(n_components);
    input::parse_function(prm, field_names[f], *function,
                          std::string("Verification/") + field_names[f]);
    return function;
  };
  if (in.compare)
  {
    displacement = parse(0, dim);
    velocity     = parse(1, dim);
    if (in.compare_stress)
      stress = parse(2, dim * (dim + 1) / 2);
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
                                       const double end_time)
{
  // At 1001 times over the run, whatever the output cadence.
  const double interval = end_time / 1000;
  if (enabled())
    for (double s = 0; s <= end_time * (1 + 1e-12); s += interval)
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
