#ifndef LME_MPM_OUTPUT_MOVING_MEAN_H
#define LME_MPM_OUTPUT_MOVING_MEAN_H

#include <lme_mpm/base/archive.h>

#include <cstddef>
#include <vector>

namespace lme_mpm
{
/**
 * The mean of a few per-step values over the last `window` seconds of simulated time:
 * the load a scene judges a test by. The force of one step chatters as particles
 * cross cells; its mean over a window fixed in time, evaluated after every step, is
 * smooth and the same whatever the output cadence (a mean over the output interval
 * is not). The steps the window covers are kept and summed again each step (a few
 * dozen), so the mean carries no round-off from earlier steps and a checkpoint
 * restores it exactly. A window of 0 keeps the last step alone.
 */
class MovingMean
{
public:
  /// @p n values per step, averaged over @p window seconds (>= 0).
  void reset(unsigned int n, double window);
  /// Adds the values @p v of a step of length @p dt (the mean is updated).
  void book(const double *v, double dt);
  void book(const std::vector<double> &v, double dt) { book(v.data(), dt); }
  /// The mean of each value over the window that ends with the last step, the time
  /// before the first step counting as zero (0 before any step).
  const std::vector<double> &mean() const { return current; }
  double mean(const unsigned int i) const { return current[i]; }
  double window() const { return span; }
  unsigned int size() const { return n_values; }

  void serialize(Archive &ar);

private:
  unsigned int n_values = 0;
  double span           = 0;
  /// The steps in the window, oldest first, from index `first` on: their lengths and
  /// values (n_values each).
  std::vector<double> lengths, values;
  std::size_t first = 0;
  std::vector<double> current;
};
} // namespace lme_mpm

#endif
