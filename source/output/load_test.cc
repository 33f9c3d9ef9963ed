#include <lme_mpm/output/load_test.h>

#include <algorithm>

namespace lme_mpm
{
void LoadTest::observe(const double load, const Energies &e, const double t)
{
  if (!on)
    return;
  if (load > peak_load)
  {
    // Judged after the last peak: before it the test is still loading.
    peak_load = load, peak_time = t, max_share = 0;
  }
  else if (e.strain > 0)
    max_share = std::max(max_share, e.kinetic / e.strain);
  last_external = e.external_work;
  last_strain   = e.strain;
}

void LoadTest::add_results(std::map<std::string, double> &r) const
{
  if (!on)
    return;
  r["device_peak_load"]             = peak_load;
  r["device_peak_time"]             = peak_time;
  r["max_kinetic_share_after_peak"] = max_share;
  r["work_of_fracture"]             = last_external - last_strain;
}
} // namespace lme_mpm
