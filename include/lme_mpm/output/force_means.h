#ifndef LME_MPM_OUTPUT_FORCE_MEANS_H
#define LME_MPM_OUTPUT_FORCE_MEANS_H

#include <deal.II/base/tensor.h>

#include <lme_mpm/base/archive.h>
#include <lme_mpm/base/dealii.h>
#include <lme_mpm/output/moving_mean.h>

#include <vector>

namespace lme_mpm
{
/**
 * Per body, two means of the contact force it receives. The load: the mean over a
 * window fixed in simulated time (`Output/Force window`) that ends at the current
 * step, updated every step, and the largest magnitude it has reached; peaks and stop
 * rules are judged on it, so they do not depend on the output cadence. The interval
 * mean: the impulse between two history rows over their time apart
 * (`force_<body>_mean_*`), whose sum over the rows is the impulse to round-off.
 */
template <int dim>
class ForceMeans
{
public:
  void reset(unsigned int n_bodies, double window);
  /// Adds the forces @p f of one step of length @p dt.
  void book(const std::vector<Tensor<1, dim>> &f, double dt);
  /// Closes a row's interval: the mean since the previous row (@p f, the last step's
  /// forces, for a row with no step behind it).
  void close_row(const std::vector<Tensor<1, dim>> &f);
  /// Per body: the force over the window ending at the last step.
  const std::vector<Tensor<1, dim>> &current() const { return window_force; }
  /// Per body: the largest magnitude of current() over the steps so far.
  const std::vector<double> &peak() const { return peak_force; }
  /// Per body: the mean force of the interval the last row closed.
  const std::vector<Tensor<1, dim>> &mean() const { return mean_force; }

  void serialize(Archive &ar)
  {
    ar(peak_force, impulse, impulse_time, window_force);
    window.serialize(ar);
    mean_force.assign(peak_force.size(), Tensor<1, dim>());
  }

private:
  std::vector<Tensor<1, dim>> mean_force, window_force;
  std::vector<double> peak_force;
  /// Per body and component since the last row, and the time it covers.
  std::vector<double> impulse;
  double impulse_time = 0;
  MovingMean window;
  std::vector<double> flat;
};
} // namespace lme_mpm

#endif
