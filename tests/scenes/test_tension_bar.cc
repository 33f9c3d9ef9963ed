// The tension bar: eigenerosion and fracture triggers on whole runs.
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/parameter_handler.h>

#include <gtest/gtest.h>

#include <lme_mpm/fracture/crack_set.h>
#include <lme_mpm/fracture/fracture_coupling.h>
#include <lme_mpm/fracture/fracture_model.h>
#include <lme_mpm/fracture/neighbourhood.h>
#include <lme_mpm/fracture/softening_law.h>

#include "tension_bar_run.h"
#include "test_helpers.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <iostream>
#include <random>

using namespace lme_mpm;
using lme_mpm_test::BarResult;
using lme_mpm_test::run_bar;

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
