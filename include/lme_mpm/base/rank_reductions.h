#ifndef LME_MPM_BASE_RANK_REDUCTIONS_H
#define LME_MPM_BASE_RANK_REDUCTIONS_H

#include <deal.II/base/exceptions.h>

#include <string>
#include <vector>

namespace lme_mpm
{
/**
 * A step that cannot go on, decided alike on every rank (from sums over the ranks, as
 * a solve's convergence is): the run stops with its output kept, on one rank or
 * several, and the message is prefixed with the step and time.
 */
DeclException1(ExcStepFailedOnAllRanks, std::string, << arg1);

/**
 * What the parts of a step need from the split of a run over MPI ranks: sums and
 * maxima over the ranks, and which grid nodes this rank reports (so that a node's
 * value, complete only where its owner holds every particle near it, is counted
 * once). A part that sums reactions or contact forces, or agrees on a length, is
 * handed this interface and never the driver; on one rank every reduction returns
 * its argument and every node is this rank's.
 */
class RankReductions
{
public:
  virtual ~RankReductions() = default;
  /// The sum over the ranks.
  virtual double sum(double v) const = 0;
  /// The sums over the ranks, element by element, in place.
  virtual void sum(std::vector<double> &v) const = 0;
  /// The largest value over the ranks.
  virtual double max(double v) const = 0;
  /// The largest values over the ranks, element by element, in place (one
  /// collective call for several maxima).
  virtual void max(std::vector<double> &v) const = 0;
  /// True if this rank reports grid node @p n (its owner).
  virtual bool owns_node(unsigned int n) const = 0;
};
} // namespace lme_mpm

#endif
