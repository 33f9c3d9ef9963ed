#ifndef LME_MPM_OUTPUT_LOAD_TEST_H
#define LME_MPM_OUTPUT_LOAD_TEST_H

#include <deal.II/base/tensor.h>

#include <lme_mpm/base/archive.h>
#include <lme_mpm/base/dealii.h>
#include <lme_mpm/output/energy_balance.h>

#include <map>
#include <string>
#include <vector>

namespace lme_mpm
{
/**
 * What a load test is judged by besides its peak, for the devices named in "Loading
 * control/Devices" (with either loading type): the largest kinetic energy over strain
 * energy after the devices' load peaked (a quasi-static test keeps it small; a test
 * that collapses turns its strain energy into motion), and the work of fracture
 * (RILEM TC-50 FMC, 1985): the external work put in up to the end of the run minus the
 * strain energy left in the specimen. The load is the devices' contact force over
 * the force window, along their prescribed direction; steps are judged, not history
 * rows, so the results do not depend on the output cadence.
 */
class LoadTest
{
public:
  void set_active(const bool a) { on = a; }
  bool active() const { return on; }
  /// After a step: the devices' load (N, over the force window) and the energies.
  void observe(double load, const Energies &e, double t);
  void add_results(std::map<std::string, double> &results) const;
  void serialize(Archive &ar)
  {
    ar(peak_load, peak_time, max_share, last_external, last_strain);
  }

private:
  bool on          = false;
  double peak_load = 0, peak_time = 0, max_share = 0;
  double last_external = 0, last_strain = 0;
};
} // namespace lme_mpm

#endif
