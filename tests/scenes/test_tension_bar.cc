// The tension bar: eigenerosion and fracture triggers on whole runs.
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/parameter_handler.h>

#include <gtest/gtest.h>

#include <lme_mpm/fracture/crack_set.h>
#include <lme_mpm/fracture/fracture_coupling.h>
#include <lme_mpm/fracture/fracture_model.h>
#include <lme_mpm/fracture/neighbourhood.h>
#include <lme_mpm/fracture/softening_law.h>

#include "test_helpers.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <iostream>
#include <random>

using namespace lme_mpm;

namespace
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
BarResult run_bar(const double h, std::vector<std::string> extra, double x0 = 0.05,
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
  const auto s = run_parameter_file(lme_mpm_test::scene("tension_bar.prm"), o, quiet);

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
} // namespace

TEST(TensionBar, EigenerosionDissipatesCriticalEnergyRelease)
{
  // Eroding a one-cell band (width h) releases h W per unit area and G_p = eps W, so
  // with eps = h (C_eps = 1) the energy per unit area is G_c. The rest of the bar is
  // 100x tougher: at failure it stores about L / eps times G_c, which rings through it.
  for (const double h : {0.005, 0.0025})
  {
    const auto r = run_bar(h, {"Material 1/Fracture/Model=eigenerosion",
                               "Material 2/Fracture/Model=eigenerosion",
                               "Material 2/Fracture/Fracture energy=5000",
                               "Material 1/Fracture/Epsilon factor=1",
                               "Material 2/Fracture/Epsilon factor=1",
                               "Boundary conditions/Constraint 2/Velocity/Function "
                               "constants=v0=0.1, tr=2e-4",
                               "Time/End time=0.0015"});
    std::cout << "eigenerosion h = " << h << ": peak " << r.peak_stress / 1e6
              << " MPa (Griffith-type sqrt(2 E G_c / h) = "
              << std::sqrt(2 * 30e9 * 50 / h) / 1e6 << "), dissipated "
              << r.dissipated_per_area << " J/m^2" << std::endl;
    EXPECT_NEAR(r.dissipated_per_area / 50.0, 1.0, 0.10) << h;
    EXPECT_NEAR(r.peak_stress / std::sqrt(2 * 30e9 * 50 / h), 1.0, 0.05) << h;
  }
}
