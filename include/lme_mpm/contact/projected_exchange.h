#ifndef LME_MPM_CONTACT_PROJECTED_EXCHANGE_H
#define LME_MPM_CONTACT_PROJECTED_EXCHANGE_H

#include <deal.II/base/tensor.h>

#include <lme_mpm/base/dealii.h>
#include <lme_mpm/particles/particle_store.h>
#include <lme_mpm/solver/grid_transfer.h>

#include <cstdint>
#include <vector>

namespace lme_mpm
{
/// Two bodies' fields at a node in contact, as the exchange sees them.
template <int dim>
struct ExchangePair
{
  unsigned int a, b;     ///< fields
  bool fixed_a, fixed_b; ///< prescribed sides: they do not give way
  Tensor<1, dim> normal; ///< from a to b
  double friction;       ///< Coulomb coefficient
  std::uint64_t key;     ///< the same node and bodies give the same key in every step
};

/**
 * The contact exchange as a velocity jump the particles carry (doc/contact.md,
 * "Contact/Exchange = projected"). Each pair receives an impulse J (on a; -J on b),
 * the particles of a field's body change velocity by sum_I N_Ip J_I / m_I over their
 * pair fields, and the displacement rates become the projection of the particles'
 * new velocities: the rates that move the particles and strain them are then the ones
 * the particles carry, so that the work of the contact and the strain energy see the
 * same motion. The impulses are found so that those projected rates no longer approach
 * along the normal (Coulomb-limited tangentially): a projected Jacobi iteration in
 * which a field's response to its own jump is the projection of a unit jump of every
 * pair field (exact for a contact that moves as one, under-relaxed for one that
 * varies from node to node), started from the impulses of the last step's pairs and
 * swept until no impulse changes by more than a tolerance. Momentum is exchanged pair
 * by pair and conserved to round-off whatever the number of sweeps.
 */
template <int dim>
class ProjectedExchange
{
public:
  /**
   * Finds every pair's impulse on a (@p impulse_on_a) in Jacobi sweeps, at most
   * @p sweeps, until no impulse changes in a sweep by more than @p tolerance times the
   * largest, and applies it: @p velocity of the particles flagged in @p touches (those
   * with a node at a shared node) and the rates and momenta of every field they reach
   * (the rates of fields above @p mass_tolerance, as the rates are projected).
   */
  void apply(const std::vector<ExchangePair<dim>> &pairs, GridTransfer<dim> &transfer,
             const ParticleStore<dim> &particles,
             const std::vector<std::uint8_t> &touches,
             std::vector<Tensor<1, dim>> &velocity,
             std::vector<Tensor<1, dim>> &impulse_on_a, unsigned int sweeps,
             double tolerance, double mass_tolerance);

  /// The sweeps the last apply() made.
  unsigned int last_sweeps() const { return sweeps_done; }

  /// The last step's impulses, which start the next step's sweeps.
  template <class Archive>
  void serialize(Archive &ar)
  {
    ar(last_keys, last_impulses);
  }

private:
  /// The particles' velocity changes for the current impulses and the momentum
  /// change of every field they reach (its rate changes by that over its mass).
  void respond(const std::vector<ExchangePair<dim>> &pairs, GridTransfer<dim> &transfer,
               const ParticleStore<dim> &particles,
               const std::vector<std::uint8_t> &touches,
               const std::vector<Tensor<1, dim>> &impulse_on_a);

  /// Starts each pair that was in contact in the last step from its impulse then;
  /// true if any was.
  bool warm_start(const std::vector<ExchangePair<dim>> &pairs,
                  std::vector<Tensor<1, dim>> &impulse_on_a) const;
  /// Keeps this step's pairs (in ascending key order) and impulses for the next.
  void remember(const std::vector<ExchangePair<dim>> &pairs,
                const std::vector<Tensor<1, dim>> &impulse_on_a);

  std::vector<Tensor<1, dim>> jump, response, delta, next;
  std::vector<double> scale;
  std::vector<std::uint8_t> in_pair;
  /// The particles flagged in `touches`, this step.
  std::vector<std::size_t> touching;
  unsigned int sweeps_done = 0;
  /// The last step's pairs (sorted keys) and their impulses.
  std::vector<std::uint64_t> last_keys;
  std::vector<Tensor<1, dim>> last_impulses;
};
} // namespace lme_mpm

#endif
