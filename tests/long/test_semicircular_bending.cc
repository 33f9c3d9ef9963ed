// The semicircular-bending crack.
#include <gtest/gtest.h>

#include "test_helpers.h"

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

TEST(SemicircularBending, VerticalNotchCrackRunsUpTheSymmetryLine)
{
  // The scene's own grid and particles; the loading roller at 20 mm/s, ten times the
  // scene's rate (doc/semicircular_bending.md gives the peak at both rates).
  const std::string tag = "scb_vertical";
  // The run goes on to 15 ms (no stop on the load): the band loses its traction as a
  // whole, so the load falls below 0.3 of its peak while the last fifth of the
  // ligament, under the roller's compression, still holds; the crack cuts it later.
  const auto r = lme_mpm_test::run_scene(
      "semicircular_bending.prm", tag,
      {"Scene/semicircular bending/Loading velocity=0.02", "Time/End time=0.015",
       "Scene/semicircular bending/Stop at load fraction=0"});
  std::cout << "peak load " << r.at("peak_force") << " N, supports "
            << r.at("peak_contact_force_left") << " / "
            << r.at("peak_contact_force_right") << " N, softened ligament share "
            << r.at("softened_ligament_share") << std::endl;
  // It broke: past its peak the load fell below 0.3 of it, and the softened band
  // reaches the top of the arc.
  {
    const auto h    = lme_mpm_test::read_history(lme_mpm_test::scratch_path(tag));
    const auto load = lme_mpm_test::column(h.first, "force_load_y");
    double peak = 0, lowest_after = std::numeric_limits<double>::max();
    for (const auto &row : h.second)
    {
      const double f = std::abs(row[load]);
      if (f > peak)
        peak = f, lowest_after = f;
      lowest_after = std::min(lowest_after, f);
    }
    std::cout << "lowest load after the peak: " << lowest_after / peak << " of it"
              << std::endl;
    EXPECT_LT(lowest_after, 0.3 * peak);
  }
  EXPECT_GT(r.at("softened_ligament_share"), 0.8);
  // Symmetry: the two supports carry the same load.
  EXPECT_NEAR(r.at("peak_contact_force_left"), r.at("peak_contact_force_right"),
              0.01 * r.at("peak_contact_force_right"));
  // The peak: Molinos et al. simulated 176 N at 2 mm/s (doc/reference_data.md section
  // 4); the scene gave 173 N at that rate and gives 175 N at this one. Without the notch
  // crack the grid ties the notch faces together and the peak is 429 N.
  EXPECT_NEAR(r.at("peak_force"), 176, 0.1 * 176);
  // The crack softens, it does not erode: no particle fails outright at onset (those
  // above f_t drop to it and follow the law). Its energy per unit area is
  // InclinedNotchCrackDissipatesFractureEnergy's: here the run goes on after the
  // specimen has broken, and the halves pressed by the rollers go on damaging.
  EXPECT_EQ(r.at("eigensoftening_snap_back_particles"), 0);
  // The energy balance closes through the peak and after it: the rollers' work goes
  // into the specimen's energies. With eight contact sweeps from zero impulses a step
  // (no tolerance, no warm start) the exchange lost 2.6e-4 J of it by the peak, a
  // drift of 0.066.
  std::cout << "max energy drift " << r.at("max_energy_drift") << std::endl;
  EXPECT_LT(r.at("max_energy_drift"), 0.02);
  // The crack path: nearly every failed particle started within 6 mm (four cells) of
  // the notch's line x = 63 mm and above the notch tip's level (y = 15 + 16.6 mm) less
  // two cells. With the faces tied, a third of them failed on the faces near the mouth.
  std::ifstream in(lme_mpm_test::scratch_path(tag) + "/failed_particles.csv");
  ASSERT_TRUE(in.good());
  std::string line;
  std::getline(in, line);
  unsigned int failed = 0, near_line = 0, above_tip = 0;
  while (std::getline(in, line))
  {
    std::stringstream s(line);
    std::vector<double> v;
    for (std::string f; std::getline(s, f, ',');)
      v.push_back(std::stod(f));
    ASSERT_GE(v.size(), 5u);
    const bool near = std::abs(v[3] - 0.063) < 0.006;
    near_line += near;
    above_tip += near && v[4] > 0.015 + 0.0166 - 0.003;
    ++failed;
  }
  std::cout << failed << " failed particles, " << near_line << " near the notch line, "
            << above_tip << " of them above the tip" << std::endl;
  ASSERT_GT(failed, 50u);
  EXPECT_GT(near_line, 0.95 * failed);
  EXPECT_GT(above_tip, 0.95 * failed);
}

TEST(SemicircularBending, InclinedNotchCrackDissipatesFractureEnergy)
{
  // 30 degrees at 20 mm/s, stopped once the load has fallen below 0.3 of its peak.
  // Particles beside the notch tip reach onset at up to 3.3 f_t; with their law scaled
  // up to that stress 72 of 237 failed outright and the crack dissipated 2.7 G_F per
  // unit area. Their stress now drops to f_t at onset and follows the law.
  const auto r = lme_mpm_test::run_scene(
      "semicircular_bending.prm", "scb_inclined",
      {"Scene/semicircular bending/Loading velocity=0.02", "Time/End time=0.02",
       "Scene/semicircular bending/Notch angle=30"});
  std::cout << "30 degrees: peak " << r.at("peak_force") << " N, energy ratio "
            << r.at("fracture_energy_ratio") << ", snapped back "
            << r.at("eigensoftening_snap_back_particles") << ", softened ligament share "
            << r.at("softened_ligament_share") << std::endl;
  EXPECT_EQ(r.at("eigensoftening_snap_back_particles"), 0);
  EXPECT_GT(r.at("fracture_energy_ratio"), 0.7);
  EXPECT_LT(r.at("fracture_energy_ratio"), 1.3);
  // Molinos et al. simulated 220 N at 2 mm/s (doc/reference_data.md section 4).
  EXPECT_NEAR(r.at("peak_force"), 220, 0.1 * 220);
  EXPECT_GT(r.at("softened_ligament_share"), 0.6);
}
