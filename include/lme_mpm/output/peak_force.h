#ifndef LME_MPM_OUTPUT_PEAK_FORCE_H
#define LME_MPM_OUTPUT_PEAK_FORCE_H

#include <lme_mpm/boundary/node_constraints.h>

#include <cmath>
#include <map>
#include <string>

namespace lme_mpm
{
/**
 * The reaction of largest magnitude of one constrained set along one component,
 * checked every step ("Output/Peak force set" = 'name:y'), with its sign, and the
 * set's imposed displacement at that moment: the peak load of a load-displacement
 * test, whether the set pulls or pushes.
 */
template <int dim>
class PeakForce
{
public:
  /// Reads 'name:component'; an empty @p entry tracks nothing.
  void parse(const std::string &entry, const NodeConstraints<dim> &constraints);
  void update(const NodeConstraints<dim> &constraints)
  {
    if (set < constraints.size() &&
        std::abs(constraints[set].reaction()[component]) > std::abs(peak))
    {
      peak                 = constraints[set].reaction()[component];
      displacement_at_peak = constraints[set].displacement()[component];
    }
  }
  void add_results(std::map<std::string, double> &results) const;

  template <class Archive>
  void serialize(Archive &ar)
  {
    ar(peak, displacement_at_peak);
  }

private:
  unsigned int set = numbers::invalid_unsigned_int, component = 0;
  double peak = 0, displacement_at_peak = 0;
};
} // namespace lme_mpm

#endif
