#ifndef LME_MPM_PARTICLES_DAMAGE_FORM_H
#define LME_MPM_PARTICLES_DAMAGE_FORM_H

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <lme_mpm/base/tensor_tools.h>
#include <lme_mpm/particles/particle_store.h>

#include <utility>

namespace lme_mpm
{
/**
 * @file
 * What damage does to a particle's stress, in the two damage forms (doc/theory.md,
 * "Damage form"): with isotropic damage (the paper's) the damage scales the whole
 * stress; with crack-oriented damage, a particle that has a crack (a nonzero
 * ParticleStore::crack_normal, fixed at onset by the fracture model) loses the
 * tractions across its crack only. The form is a particle's data, not a flag of the
 * run, so the forces, the energies and the output read it without a virtual call per
 * particle, and the fracture models, which set it, share these functions with them.
 */

/// The share of its stress particle @p p carries with isotropic damage: 1 - damage,
/// and 0 once failed.
template <int dim>
inline double stress_factor(const ParticleStore<dim> &particles, const std::size_t p)
{
  return particles.failed[p] ? 0.0 : 1 - particles.damage[p];
}

/// True if particle @p p has a crack of crack-oriented damage (never in a run without
/// a fracture model, whose store drops the crack normals).
template <int dim>
inline bool has_crack_normal(const ParticleStore<dim> &particles, const std::size_t p)
{
  return !particles.crack_normal.empty() && particles.crack_normal[p].norm_square() > 0;
}

/**
 * The stress a particle with a crack of normal @p n carries, from its undamaged
 * stress @p sigma: the derivative of the energy density
 *   psi = sigma : eps / 2 - chi <s>+^2 / (2 M) - chi |tau|^2 / (2 mu),
 * with s = n . sigma . n the normal traction across the crack (only while it pulls
 * the faces apart), tau = (I - n n) sigma n the shear traction on the crack plane, and
 * chi the damage (@p chi, 1 once failed):
 *   sigma - chi <s>+ (c I + (1 - c) n n) - chi (n tau + tau n),
 * with c = lambda / M (@p coupling). A closed crack carries its compression, and the
 * stress parallel to the crack is kept; a fully open one carries no traction.
 */
template <int dim>
inline SymmetricTensor<2, dim> cracked_stress(const SymmetricTensor<2, dim> &sigma,
                                              const Tensor<1, dim> &n, const double chi,
                                              const double coupling)
{
  const Tensor<1, dim> t      = sigma * n;
  const double s              = t * n;
  const Tensor<1, dim> tau    = t - s * n;
  SymmetricTensor<2, dim> out = sigma;
  const double open           = s > 0 ? chi * s : 0.0;
  for (unsigned int i = 0; i < dim; ++i)
    for (unsigned int j = i; j < dim; ++j)
      out[i][j] -= open * ((i == j ? coupling : 0.0) + (1 - coupling) * n[i] * n[j]) +
                   chi * (n[i] * tau[j] + tau[i] * n[j]);
  return out;
}

/**
 * The effective stress of particle @p p: what the internal forces use, so what the
 * output reports (`stress` is the undamaged one). Isotropic damage: (1 - damage)
 * sigma, and 0 once failed. Crack-oriented damage: cracked_stress().
 */
template <int dim>
inline SymmetricTensor<2, dim> effective_stress(const ParticleStore<dim> &particles,
                                                const std::size_t p)
{
  if (has_crack_normal(particles, p))
    return cracked_stress(particles.stress[p], particles.crack_normal[p],
                          particles.failed[p] ? 1.0 : particles.damage[p],
                          particles.crack_coupling[p]);
  return stress_factor(particles, p) * particles.stress[p];
}

/**
 * The elastic energy per unit volume particle @p p stores, effective stress : strain
 * / 2 (the energy density psi whose derivative the effective stress is, for a
 * material linear in the strain).
 */
template <int dim>
inline double stored_energy_density(const ParticleStore<dim> &particles,
                                    const std::size_t p)
{
  if (has_crack_normal(particles, p))
    return 0.5 * (effective_stress(particles, p) * particles.strain[p]);
  return 0.5 * stress_factor(particles, p) * (particles.stress[p] * particles.strain[p]);
}
/**
 * The strain and stress that drive particle @p p's damage: the normal strain and
 * stress across its crack once it has an oriented one, otherwise its max principal
 * strain and @p max_principal_stress (the max principal value of its undamaged
 * stress, which the caller has at hand).
 */
template <int dim>
inline std::pair<double, double> damage_drive(const ParticleStore<dim> &particles,
                                              const std::size_t p,
                                              const double max_principal_stress)
{
  if (!has_crack_normal(particles, p))
    return {max_principal(particles.strain[p]), max_principal_stress};
  const Tensor<1, dim> &n = particles.crack_normal[p];
  return {n * (particles.strain[p] * n), n * (particles.stress[p] * n)};
}

/**
 * The energy per unit volume that full damage takes from particle @p p (secant
 * unloading: the energy density is linear in the damage, so a damage increment d chi
 * dissipates d chi times this): sigma : eps / 2 with isotropic damage, the part across
 * the crack with an oriented one.
 */
template <int dim>
inline double damageable_energy_density(const ParticleStore<dim> &particles,
                                        const std::size_t p)
{
  const SymmetricTensor<2, dim> &sigma = particles.stress[p];
  if (!has_crack_normal(particles, p))
    return 0.5 * (sigma * particles.strain[p]);
  return 0.5 * ((sigma - cracked_stress(sigma, particles.crack_normal[p], 1.0,
                                        particles.crack_coupling[p])) *
                particles.strain[p]);
}
} // namespace lme_mpm

#endif
