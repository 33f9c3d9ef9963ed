// Tension-bar studies: the fracture energy at three resolutions, on graded grids and
// with the LME crack band.
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

TEST(TensionBar, EigensofteningDissipatesFractureEnergyAtThreeResolutions)
{
  // Acceptance: per unit crack area the dissipated energy is G_F = 50 N/m within 5 %,
  // the peak stress f_t = 3 MPa within 5 %, for linear and exponential softening.
  for (const std::string law : {"linear", "exponential"})
    for (const double h : {0.005, 0.0025, 0.00125})
    {
      const auto r =
          run_bar(h, {"Material 1/Fracture/Softening law=" + law,
                      "Material 2/Fracture/Softening law=" + law,
                      law == "linear" ? "Time/End time=0.005" : "Time/End time=0.0125"});
      std::cout << law << " h = " << h << ": peak " << r.peak_stress / 1e6
                << " MPa, dissipated " << r.dissipated_per_area << " J/m^2" << std::endl;
      EXPECT_NEAR(r.dissipated_per_area / 50.0, 1.0, 0.05) << law << " h " << h;
      EXPECT_NEAR(r.peak_stress / 3e6, 1.0, 0.05) << law << " h " << h;
      EXPECT_GT(r.failed, 0) << law << " h " << h;
    }
}

TEST(TensionBar, LmeCrackBandIsObjectiveOffTheCellLines)
{
  // LME spreads a crack's jump over four particle columns (gamma = 1.8) or two (3.5),
  // unequally. 'Band width = 0' takes the band's width from the functions (1.32 and
  // 1.02 cells at two Gauss points per cell) and the band's particles lose their
  // traction together, so a crack dissipates G_F and carries nothing once open,
  // whatever the resolution and wherever the crack lies against the cell lines. The
  // weak zone must hold the four columns: two cells centred on a cell (half a cell off
  // the cell lines), and four cells on the cell lines. With a one-cell band and each
  // particle on its own opening, gamma = 1.8 dissipated 1.30 G_F here and still carried
  // 16 % of the peak at the end (stress locking), more the longer the crack opened.
  struct Case
  {
    double gamma, h;
    unsigned int cells;
    double offset;
  };
  std::vector<Case> cases;
  for (const double gamma : {1.8, 3.5})
  {
    for (const double h : {0.005, 0.0025, 0.00125})
      cases.push_back({gamma, h, 2, 0.5});
    cases.push_back({gamma, 0.0025, 4, 0.0});
  }
  for (const auto &c : cases)
  {
    const double x0 = 0.05 - 0.5 * c.cells * c.h + c.offset * c.h,
                 x1 = x0 + c.cells * c.h;
    const auto r    = run_bar(c.h,
                              {"Shape functions/Type=lme",
                               "Shape functions/LME gamma=" + std::to_string(c.gamma)},
                              x0, x1);
    std::ostringstream what;
    what << "gamma " << c.gamma << ", h " << c.h << ", " << c.cells << "-cell zone at "
         << x0;
    std::cout << what.str() << ": peak " << r.peak_stress / 3e6 << " f_t, dissipated "
              << r.dissipated_per_area / 50.0 << " G_F, load at the end "
              << r.end_load_share << " of the peak" << std::endl;
    EXPECT_NEAR(r.dissipated_per_area / 50.0, 1.0, 0.05) << what.str();
    EXPECT_NEAR(r.peak_stress / 3e6, 1.0, 0.05) << what.str();
    EXPECT_LT(std::abs(r.end_load_share), 0.03) << what.str();
  }
}

TEST(TensionBar, GradedGridDissipatesFractureEnergyInCoarseAndFineCells)
{
  // The bar on a grid with 2.5 mm cells for x < 0.05 m and 5 mm cells beyond (5 mm
  // high, so every cell's short side is along the bar), the one-cell weak zone in a
  // fine cell or in a coarse one. With the band width and eps tied to the grid's
  // smallest spacing, the crack in a coarse cell dissipated 2 G_F.
  for (const bool coarse : {false, true})
  {
    const double h = coarse ? 0.005 : 0.0025, x0 = coarse ? 0.07 : 0.025;
    const std::string zone =
        "rectangle(" + std::to_string(x0) + ", 0, " + std::to_string(x0 + h) + ", 0.005)";
    const std::string dir =
        lme_mpm_test::scratch(coarse ? "graded_bar_coarse" : "graded_bar_fine");
    std::ostringstream quiet;
    const auto s       = run_parameter_file(lme_mpm_test::scene("tension_bar.prm"),
                                            {"Grid/Step sizes x=20*0.0025, 10*0.005",
                                             "Grid/Step sizes y=0.005", "Body 1/Shape=" + zone,
                                             "Body 2/Holes=" + zone, "Output/Directory=" + dir,
                                             "Output/Verbosity=0"},
                                            quiet);
    const auto history = lme_mpm_test::read_history(dir);
    const auto &names  = history.first;
    const auto i_diss =
        std::find(names.begin(), names.end(), "dissipated_energy") - names.begin();
    const double per_area = history.second.back()[i_diss] / (0.005 * 0.005);
    std::cout << (coarse ? "coarse" : "fine") << " cell (h = " << h << "): dissipated "
              << per_area << " J/m^2" << std::endl;
    EXPECT_NEAR(per_area / 50.0, 1.0, 0.02) << (coarse ? "coarse" : "fine");
    EXPECT_GT(s.at("failed_particles"), 0);
  }
}

TEST(TensionBar, FixedBandWidthIsMeshDependent)
{
  // Holding h_eps = 10 mm while the crack localises in one cell of size h: the band
  // dissipates about G_F h / h_eps, so the energy is not objective.
  const auto coarse =
      run_bar(0.005, {"Material 1/Fracture/Band width=0.01",
                      "Material 2/Fracture/Band width=0.01", "Time/End time=0.008"});
  const auto fine =
      run_bar(0.0025, {"Material 1/Fracture/Band width=0.01",
                       "Material 2/Fracture/Band width=0.01", "Time/End time=0.008"});
  std::cout << "h_eps fixed at 10 mm: dissipated " << coarse.dissipated_per_area
            << " (h = 5 mm), " << fine.dissipated_per_area << " (h = 2.5 mm) J/m^2"
            << std::endl;
  EXPECT_NEAR(coarse.dissipated_per_area, 50.0 * 0.5, 2.5);
  EXPECT_NEAR(fine.dissipated_per_area, 50.0 * 0.25, 2.5);
}

TEST(InclinedTensionBar, CrackAcrossTheGridDissipatesFractureEnergy)
{
  // The bar of prm/inclined_tension_bar.prm at an angle to the grid, so that its crack
  // crosses cells diagonally: with the band's opening integrated across the band, the
  // crack dissipates G_F per unit area and the bar peaks at the weak zone's f_t, for
  // each family of functions (doc/validation.md has the full table). Before, with the
  // most-open particle's opening shared along the band, linear functions dissipated
  // 1.26 G_F at 30 degrees and 1.31 at 45.
  struct Case
  {
    std::string type, gamma, angle;
  };
  for (const Case &c :
       {Case{"linear", "", "30"}, Case{"bspline", "", "45"}, Case{"lme", "1.8", "30"}})
  {
    std::vector<std::string> o = {"Shape functions/Type=" + c.type,
                                  "Scene/inclined tension bar/Angle=" + c.angle};
    if (!c.gamma.empty())
      o.push_back("Shape functions/LME gamma=" + c.gamma);
    const auto s = lme_mpm_test::run_scene("inclined_tension_bar.prm", "inclined_bar", o);
    const std::string what = c.type + c.gamma + " at " + c.angle + " degrees";
    std::cout << what << ": dissipated / (G_F W t) = " << s.at("fracture_energy_ratio")
              << ", peak / f_t = " << s.at("peak_stress") / 2.7e6 << std::endl;
    EXPECT_NEAR(s.at("fracture_energy_ratio"), 1.0, 0.05) << what;
    EXPECT_NEAR(s.at("peak_stress") / 2.7e6, 1.0, 0.05) << what;
    EXPECT_EQ(s.at("eigensoftening_snap_back_particles"), 0) << what;
  }
}

TEST(InclinedTensionBar, CrackTurnedOutOfTheGridPlanesIn3D)
{
  // The 3D bar (prm/inclined_tension_bar_3d.prm) turned by 30 degrees about z and
  // tilted 35 degrees out of the x-y plane: its crack crosses the cells along no grid
  // plane, and the measured band still dissipates G_F per unit crack area (W^2) at the
  // weak zone's f_t (doc/validation.md has the table for every family).
  const auto s =
      lme_mpm_test::run_scene("inclined_tension_bar_3d.prm", "inclined_bar_3d",
                              {"Scene/inclined tension bar/Angle=30",
                               "Scene/inclined tension bar/Out-of-plane angle=35"});
  std::cout << "3D bar at (30, 35) degrees: dissipated / (G_F W^2) = "
            << s.at("fracture_energy_ratio")
            << ", peak / f_t = " << s.at("peak_stress") / 2.7e6 << std::endl;
  EXPECT_NEAR(s.at("crack_area"), 1e-4, 1e-12);
  EXPECT_NEAR(s.at("fracture_energy_ratio"), 1.0, 0.05);
  EXPECT_NEAR(s.at("peak_stress") / 2.7e6, 1.0, 0.05);
  EXPECT_EQ(s.at("eigensoftening_snap_back_particles"), 0);
}
