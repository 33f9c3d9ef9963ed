#ifndef LME_MPM_CONTACT_CONTACT_PAIRS_H
#define LME_MPM_CONTACT_CONTACT_PAIRS_H

#include <deal.II/base/tensor.h>

#include <lme_mpm/contact/body_fields.h>
#include <lme_mpm/solver/grid_transfer.h>

#include <cstdint>
#include <string>
#include <vector>

namespace lme_mpm
{
/// Two bodies' fields at a shared node, in contact this step.
template <int dim>
struct ContactPair
{
  unsigned int a, b; // fields
  unsigned int body_a, body_b;
  Tensor<1, dim> normal; // from a to b
  double friction;
  bool held; // stuck at the end of the last step
  std::uint64_t key;
};

/**
 * Which fields touch, and the nodal exchange between them (Bardenhagen et al. 2000,
 * 2001). At a shared node, two bodies are in contact when the particle volume the
 * node sees, sum_p N_Ip V_p over all bodies, fills a set fraction of the node's own
 * volume (a gap between the bodies leaves a hole in it: doc/contact.md) and each
 * fills a tenth of it; the normal comes from the fields' volume gradients. Bodies in
 * contact that approach along the normal exchange the momentum that removes their
 * normal relative velocity, with Coulomb friction on the tangential part (a
 * coefficient per pair of bodies); separating bodies move freely. A prescribed body
 * has infinite mass in the exchange.
 */
template <int dim>
class ContactPairs
{
public:
  using Pair = ContactPair<dim>;

  /**
   * @p normal_rule: 'larger gradient', 'larger volume' or 'difference'
   * (Contact/Normal); @p friction: the coefficient of every pair, then
   * @p pair_friction ('a-b: mu; ...', Contact/Pair friction coefficients) per pair;
   * throws ExcBadInput naming the entry on a malformed pair.
   */
  void set_up(const BackgroundGrid<dim> &grid, const std::string &normal_rule,
              double volume_fraction, double friction, const std::string &pair_friction,
              unsigned int n_bodies, double thickness);

  /// Pairs in contact at the shared nodes of @p fields, from this step's rates.
  void find(const BodyFields<dim> &fields, const Bodies<dim> &bodies,
            const GridTransfer<dim> &transfer, const ParticleStore<dim> &particles,
            double mass_tolerance);

  const std::vector<Pair> &list() const { return pairs; }
  std::size_t size() const { return pairs.size(); }
  bool empty() const { return pairs.empty(); }

  /**
   * Changes x on every approaching pair so that the normal relative velocity
   * velocity(F) vanishes (Coulomb-limited tangentially); x changes the velocity by
   * @p scale times its own change. On the rates, pairs that stuck at the end of the
   * last step are held together tangentially. record(pair, impulse on a, stuck) sees
   * every pair.
   */
  template <class Velocity, class Record>
  void exchange(std::vector<Tensor<1, dim>> &x, const std::vector<double> &mass,
                const Velocity &velocity, double scale, bool rate_stage,
                const Bodies<dim> &bodies, const Record &record) const;

  /// The pairs that stick at the end of this step: cleared, then added in ascending
  /// key order (the pairs' order), so the list stays sorted.
  void clear_stuck() { stuck_pairs.clear(); }
  void add_stuck(const Pair &pair) { stuck_pairs.push_back(pair.key); }

  template <class Archive>
  void serialize(Archive &ar)
  {
    ar(stuck_pairs);
  }

private:
  /// The node's share of its cells (m^3; m^2 times the thickness in 2D).
  double node_volume(unsigned int I) const;
  /// Mass gradient and particle volume of every body's field at the shared nodes.
  void measure_volumes(const BodyFields<dim> &fields, const GridTransfer<dim> &transfer,
                       const ParticleStore<dim> &particles);

  const BackgroundGrid<dim> *grid = nullptr;
  unsigned int normal_rule        = 1; // larger gradient, larger volume, difference
  unsigned int n_bodies           = 0;
  double volume_fraction = 0.9, thickness = 1;
  /// friction[a * n_bodies + b]
  std::vector<double> friction;
  std::vector<Tensor<1, dim>> volume_gradient;
  std::vector<double> field_volume;
  std::vector<Pair> pairs;
  /// The pairs (grid node, bodies) that stuck at the end of the last step, sorted.
  std::vector<std::uint64_t> stuck_pairs;
};

template <int dim>
template <class Velocity, class Record>
void ContactPairs<dim>::exchange(std::vector<Tensor<1, dim>> &x,
                                 const std::vector<double> &mass,
                                 const Velocity &velocity, const double scale,
                                 const bool rate_stage, const Bodies<dim> &bodies,
                                 const Record &record) const
{
  for (const Pair &pair : pairs)
  {
    const Tensor<1, dim> dv = velocity(pair.a) - velocity(pair.b);
    const double vn         = dv * pair.normal;
    // A pair that stuck at the end of the last step keeps its fields together over
    // this step's displacement: its rates lose their tangential difference even
    // where the rates, interpolated from particles, no longer approach.
    const bool held = rate_stage && pair.held;
    if (!(vn > 0) && !held)
    {
      record(pair, Tensor<1, dim>(), false);
      continue; // separating or at rest along the normal
    }
    const double approach = std::max(vn, 0.0);
    const bool fixed_a    = bodies.prescribed(pair.body_a),
               fixed_b    = bodies.prescribed(pair.body_b);
    const double ma = mass[pair.a], mb = mass[pair.b];
    // Reduced mass of the pair; a prescribed side does not give way.
    const double mr         = fixed_b ? ma : fixed_a ? mb : ma * mb / (ma + mb);
    const Tensor<1, dim> vt = dv - vn * pair.normal;
    const double vt_norm    = vt.norm();
    // Stick if the tangential impulse stays within mu times the normal one.
    const bool stick                  = held || !(vt_norm > pair.friction * approach);
    const double slip                 = stick ? 1.0 : pair.friction * approach / vt_norm;
    const Tensor<1, dim> impulse_on_a = -mr * (approach * pair.normal + slip * vt);
    if (!fixed_a)
      x[pair.a] += impulse_on_a / (ma * scale);
    if (!fixed_b)
      x[pair.b] -= impulse_on_a / (mb * scale);
    // Only a frictional pair is held: a frictionless one has no tangential bond.
    record(pair, impulse_on_a, stick && approach > 0 && pair.friction > 0);
  }
}
} // namespace lme_mpm

#endif
