#include <lme_mpm/base/input.h>
#include <lme_mpm/base/parameters.h>
#include <lme_mpm/materials/linear_elastic.h>
#include <lme_mpm/particles/damage_form.h>

#include <cmath>

namespace lme_mpm
{
namespace materials
{
namespace
{
/// The material's entries, declared and read from this one list.
struct LinearElasticEntries
{
  double E = 1e9, nu = 0.2;
  void entries(EntryList &list)
  {
    list.add("Young's modulus", E, "1e9", Patterns::Double(0),
             "Young's modulus E (Pa), > 0.");
    list.add("Poisson's ratio", nu, "0.2", Patterns::Double(-1, 0.5),
             "Poisson's ratio nu, in (-1, 0.5).");
  }
};
} // namespace

template <int dim>
void LinearElastic<dim>::declare_parameters(ParameterHandler &prm)
{
  EntryList::declare<LinearElasticEntries>(prm);
}

template <int dim>
LinearElastic<dim>::LinearElastic(ParameterHandler &prm, const MaterialContext &context)
{
  const auto in = EntryList::parse<LinearElasticEntries>(prm);
  E             = in.E;
  nu            = in.nu;
  input::require_range(E, 0, std::numeric_limits<double>::max(), true,
                       context.section + "/Young's modulus");
  input::require_range(nu, -1, 0.5, true, context.section + "/Poisson's ratio");
  rho     = context.density;
  section = context.section;
  setup(context.plane);
}

template <int dim>
LinearElastic<dim>::LinearElastic(const double density, const double youngs_modulus,
                                  const double poisson_ratio, const PlaneAssumption plane)
    : rho(density), E(youngs_modulus), nu(poisson_ratio)
{
  setup(plane);
}

template <int dim>
void LinearElastic<dim>::setup(const PlaneAssumption plane)
{
  mu                   = E / (2 * (1 + nu));
  const double lambda3 = E * nu / ((1 + nu) * (1 - 2 * nu));
  // Plane stress condenses out sigma_zz = 0.
  lambda_eff = (dim == 2 && plane == PlaneAssumption::plane_stress)
                   ? 2 * mu * lambda3 / (lambda3 + 2 * mu)
                   : lambda3;
}

template <int dim>
double LinearElastic<dim>::wave_speed() const
{
  return std::sqrt((lambda_eff + 2 * mu) / rho);
}

template <int dim>
std::vector<input::EntryValue> LinearElastic<dim>::wave_speed_inputs() const
{
  return {{section + "/Young's modulus", E, "Pa", 1e3, 1e13},
          {section + "/Poisson's ratio", nu, "", -1, 0.5}};
}

template <int dim>
void LinearElastic<dim>::update_stress(ParticleStore<dim> &particles,
                                       const std::size_t begin, const std::size_t end,
                                       const unsigned int material_id) const
{
  for (std::size_t p = begin; p < end; ++p)
    if (particles.material_id[p] == material_id && !particles.failed[p])
    {
      const SymmetricTensor<2, dim> &de = particles.strain_increment[p];
      particles.stress[p] +=
          lambda_eff * trace(de) * unit_symmetric_tensor<dim>() + 2 * mu * de;
    }
}

template <int dim>
double LinearElastic<dim>::strain_energy(const ParticleStore<dim> &particles,
                                         const std::size_t begin, const std::size_t end,
                                         const unsigned int material_id) const
{
  double w = 0;
  for (std::size_t p = begin; p < end; ++p)
    if (particles.material_id[p] == material_id)
      w += has_crack_normal(particles, p)
               ? particles.initial_volume[p] * stored_energy_density(particles, p)
               : 0.5 * (1 - particles.damage[p]) * particles.initial_volume[p] *
                     (particles.stress[p] * particles.strain[p]);
  return w;
}

template class LinearElastic<2>;
template class LinearElastic<3>;
} // namespace materials
} // namespace lme_mpm

using lme_mpm::materials::LinearElastic;
LME_MPM_REGISTER_MATERIAL(LinearElastic, "linear elastic",
                          "isotropic linear elasticity in small strain (Young's modulus, "
                          "Poisson's ratio); plane strain or plane stress in 2D.")
