#ifndef LME_MPM_CONTACT_CRACK_FACE_CONTACT_H
#define LME_MPM_CONTACT_CRACK_FACE_CONTACT_H

#include <lme_mpm/contact/body_fields.h>
#include <lme_mpm/fracture/crack_set.h>
#include <lme_mpm/solver/explicit_newmark.h>
#include <lme_mpm/solver/grid_transfer.h>

#include <cstdint>
#include <vector>

namespace lme_mpm
{
/**
 * Frictionless contact between the two fields of a crack node: where the faces have
 * closed (the fields' mean displacements no longer open the crack) and approach
 * each other along the crack normal, both take the mass-weighted mean normal
 * velocity, which conserves momentum. Applied to the displacement rates, then to
 * the accelerations with the trial end-of-step velocity that the Newmark corrector
 * gives the field before contact, v + dt ((1 - gamma) a^n + gamma a) (at gamma = 1/2
 * the rate before contact plus gamma dt a): the faces' end-of-step normal velocities
 * become equal, so the particles lose their approach velocity, and faces pulled apart
 * by their forces separate even when their rates were made equal.
 */
template <int dim>
class CrackFaceContact
{
public:
  CrackFaceContact(const CrackSet<dim> &cracks, GridTransfer<dim> &transfer,
                   const ParticleStore<dim> &particles);

  /// Where the particle-to-grid transfer marks the particles whose support has a
  /// crack node (sized for this step).
  std::uint8_t *touched(std::size_t n_particles);

  /**
   * With multi-field contact the cracked body's field at a grid node need not be the
   * node's own index (another body may hold it): @p fields tells which it is, or that
   * the body does not reach the node this step. Without it the node's own field is
   * the near face.
   */
  void set_body_fields(const BodyFields<dim> &fields) { body_fields = &fields; }

  /// Decides which faces are closed and makes their approaching rates equal.
  void on_rates(double mass_tolerance);
  /// The same on the accelerations, for the trial end-of-step velocity of the
  /// corrector, from the momentum and mass-weighted acceleration before contact.
  void on_accelerations(const ExplicitNewmark &newmark, double dt);

private:
  /// Changes x on the closed, approaching pairs so that their normal velocities
  /// velocity(I), which change by @p scale times the change of x, become equal.
  template <class Velocity>
  void equalise(std::vector<Tensor<1, dim>> &x, const Velocity &velocity,
                double scale) const;

  const CrackSet<dim> &cracks;
  GridTransfer<dim> &transfer;
  const ParticleStore<dim> &particles;
  const BodyFields<dim> *body_fields = nullptr;
  /// Per crack node this step: the near face's field (see set_near_field()).
  std::vector<unsigned int> near;
  std::vector<std::uint8_t> touches_crack, faces_closed;
  std::vector<Tensor<1, dim>> nodal_displacement;
};
} // namespace lme_mpm

#endif
