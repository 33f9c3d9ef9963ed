#ifndef LME_MPM_MATERIALS_LINEAR_ELASTIC_H
#define LME_MPM_MATERIALS_LINEAR_ELASTIC_H

#include <deal.II/base/symmetric_tensor.h>

#include <lme_mpm/materials/material.h>

namespace lme_mpm
{
namespace materials
{
/**
 * Isotropic linear elasticity in small strain, sigma += C : d(epsilon). In 2D the
 * in-plane stiffness is that of plane strain or of plane stress. Exposed in a
 * header so that new materials (for example a damaged one) can reuse it.
 */
template <int dim>
class LinearElastic : public Material<dim>
{
public:
  static void declare_parameters(ParameterHandler &prm);
  LinearElastic(ParameterHandler &prm, const MaterialContext &context);
  LinearElastic(double density, double youngs_modulus, double poisson_ratio,
                PlaneAssumption plane);

  std::string name() const override { return "linear elastic"; }
  double density() const override { return rho; }
  double wave_speed() const override;
  /// Young's modulus (physical from 1e3 to 1e13 Pa: foams to diamond) and Poisson's
  /// ratio.
  std::vector<input::EntryValue> wave_speed_inputs() const override;
  void update_stress(ParticleStore<dim> &particles, std::size_t begin, std::size_t end,
                     unsigned int material_id) const override;
  double strain_energy(const ParticleStore<dim> &particles, std::size_t begin,
                       std::size_t end, unsigned int material_id) const override;

private:
  void setup(PlaneAssumption plane);

  double rho = 0, E = 0, nu = 0, mu = 0, lambda_eff = 0;
  /// "Material N/linear elastic", for messages.
  std::string section = "Material/linear elastic";
};
} // namespace materials
} // namespace lme_mpm

#endif
