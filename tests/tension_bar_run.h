// The tension bar of prm/tension_bar.prm one cell high, run by the scene test and the
// long studies alike.
#ifndef LME_MPM_TESTS_TENSION_BAR_RUN_H
#define LME_MPM_TESTS_TENSION_BAR_RUN_H

#include <lme_mpm/simulation/run.h>

#include "test_helpers.h"

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

namespace lme_mpm_test
{
/// Runs the tension bar one cell high at cell size h; returns history columns.
struct BarResult
{
  double peak_stress = 0, dissipated_per_area = 0, failed = 0;
  /// The load at the end, as a fraction of the peak: what still crosses the crack.
  double end_load_share = 0;
};

/// The bar with its weak zone (material 1) over [x0, x1] (default: the cell at x = 0.05
/// m).
inline BarResult run_bar(const double h, std::vector<std::string> extra, double x0 = 0.05,
                         double x1 = -1)
{
  if (x1 < 0)
    x1 = x0 + h;
  const std::string zone = "rectangle(" + std::to_string(x0) + ", 0, " +
                           std::to_string(x1) + ", " + std::to_string(h) + ")",
                    hs       = std::to_string(h);
  std::vector<std::string> o = {
      "Grid/Cell size=" + hs, "Grid/Upper corner=0.1, " + hs, "Body 1/Shape=" + zone,
      "Body 2/Shape=rectangle(0, 0, 0.1, " + hs + ")", "Body 2/Holes=" + zone};
  o.insert(o.end(), extra.begin(), extra.end());
  const std::string dir = lme_mpm_test::scratch("bar_" + hs);
  o.push_back("Output/Directory=" + dir);
  o.push_back("Output/Verbosity=0");
  std::ostringstream quiet;
  const auto s =
      lme_mpm::run_parameter_file(lme_mpm_test::scene("tension_bar.prm"), o, quiet);

  const auto history = lme_mpm_test::read_history(dir);
  const auto &names  = history.first;
  const auto &rows   = history.second;
  const auto col     = [&](const std::string &n)
  { return std::find(names.begin(), names.end(), n) - names.begin(); };
  const auto i_force = col("force_right_x"), i_diss = col("dissipated_energy");
  const double area = 0.005 * h, diss = rows.back()[i_diss];
  BarResult r;
  // The peak of the loading branch: up to the row where the band has dissipated 90 %
  // of its energy (after it the separated halves ring).
  for (const auto &v : rows)
  {
    r.peak_stress = std::max(r.peak_stress, v[i_force] / area);
    if (v[i_diss] >= 0.9 * diss)
      break;
  }
  r.dissipated_per_area = diss / area;
  r.failed              = s.at("failed_particles");
  r.end_load_share      = rows.back()[i_force] / (r.peak_stress * area);
  return r;
}
} // namespace lme_mpm_test

#endif
