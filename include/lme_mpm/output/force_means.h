#ifndef LME_MPM_OUTPUT_FORCE_MEANS_H
#define LME_MPM_OUTPUT_FORCE_MEANS_H

#include <deal.II/base/tensor.h>

#include <lme_mpm/base/dealii.h>

#include <vector>

namespace lme_mpm
{
/**
 * Per body, the mean of a force over the steps between two history rows (the impulse
 * over the elapsed time) and the largest of these means: the force of one step
 * chatters as particles cross cells, its mean over an output interval is the load.
 */
template <int dim>
class ForceMeans
{
public:
  void reset(unsigned int n_bodies);
  /// Adds the forces @p f of one step of length @p dt.
  void book(const std::vector<Tensor<1, dim>> &f, double dt);
  /**
   * Closes a row's interval: the mean since the previous row (@p f, the last step's
   * forces, for a row with no step behind it) and, with @p track_peak, the peaks.
   */
  void close_row(const std::vector<Tensor<1, dim>> &f, bool track_peak);
  /// Per body: the mean force of the interval the last row closed.
  const std::vector<Tensor<1, dim>> &mean() const { return mean_force; }
  /// Per body: the largest magnitude of those means so far.
  const std::vector<double> &peak() const { return peak_force; }

  template <class Archive>
  void serialize(Archive &ar)
  {
    ar(peak_force, impulse, impulse_time);
    mean_force.assign(peak_force.size(), Tensor<1, dim>());
  }

private:
  std::vector<Tensor<1, dim>> mean_force;
  std::vector<double> peak_force;
  /// Per body and component since the last row, and the time it covers.
  std::vector<double> impulse;
  double impulse_time = 0;
};
} // namespace lme_mpm

#endif
