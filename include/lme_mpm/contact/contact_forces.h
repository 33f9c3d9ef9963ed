#ifndef LME_MPM_CONTACT_CONTACT_FORCES_H
#define LME_MPM_CONTACT_CONTACT_FORCES_H

#include <deal.II/base/tensor.h>

#include <lme_mpm/base/dealii.h>
#include <lme_mpm/base/rank_reductions.h>

#include <vector>

namespace lme_mpm
{
/**
 * The contact force each body receives in one step: booked pair by pair at the nodes
 * this rank reports (so a pair counts once over the ranks), then summed over the
 * ranks. Its means over output intervals are the output's (ForceMeans).
 */
template <int dim>
class ContactForces
{
public:
  void reset(const unsigned int n_bodies) { force.assign(n_bodies, Tensor<1, dim>()); }
  /// Distributed runs: only the nodes this rank owns book forces, then summed.
  void set_ranks(const RankReductions &r) { ranks = &r; }
  /// True if a pair at grid node @p node is booked on this rank.
  bool reports(const unsigned int node) const { return !ranks || ranks->owns_node(node); }

  /// Starts a step's forces at zero.
  void clear() { force.assign(force.size(), Tensor<1, dim>()); }
  /// Books @p f on body @p a and -f on body @p b.
  void add(const unsigned int a, const unsigned int b, const Tensor<1, dim> &f)
  {
    force[a] += f;
    force[b] -= f;
  }
  /// Sums the step's forces over the ranks.
  void sum_over_ranks();
  /// Per body: the force of the step (N).
  const std::vector<Tensor<1, dim>> &step() const { return force; }

private:
  const RankReductions *ranks = nullptr;
  std::vector<Tensor<1, dim>> force;
};
} // namespace lme_mpm

#endif
