// The three-point-bending scene: a seated, balanced and symmetric elastic beam, the
// CMOD servo on it, 3D, and its input.
#include <gtest/gtest.h>

#include "test_helpers.h"

#include <cmath>

namespace
{
/// The coarse, fast beam: 5 mm cells (particles 2.5 mm apart; the notch is widened to
/// one cell to remove the two columns beside mid-length), elastic, for 2 ms.
std::vector<std::string> coarse()
{
  return {"Grid/Cell size=0.005", "Scene/three point bending/Notch width=0.005",
          "Scene/three point bending/CMOD gauge length=0.015", "Time/End time=0.002",
          "Material 1/Fracture/Model=none"};
}

std::vector<double>
column(const std::pair<std::vector<std::string>, std::vector<std::vector<double>>> &h,
       const std::string &name)
{
  const auto c = lme_mpm_test::column(h.first, name);
  std::vector<double> v;
  for (const auto &row : h.second)
    v.push_back(row[c]);
  return v;
}
} // namespace

TEST(ThreePointBending, SeatedBeamIsBalancedAndSymmetric)
{
  // Under a constant deflection rate the elastic beam is loaded from the first steps
  // (the supports are seated on it, so it does not fall onto them), the supports'
  // vertical forces sum to the load within 2 % and share it within 1 %, and the load
  // grows in proportion to the deflection (secant stiffness within 5 % over the last
  // half of the run).
  const std::string tag = "tpb_balance";
  auto o                = coarse();
  o.push_back("Scene/three point bending/Control=deflection");
  const auto r = lme_mpm_test::run_scene("three_point_bending.prm", tag, o);
  EXPECT_GT(r.at("seating_left"), 0);
  EXPECT_NEAR(r.at("seating_left"), r.at("seating_right"), 1e-12);
  const auto h = lme_mpm_test::read_history(lme_mpm_test::scratch_path(tag));
  const auto t = column(h, "time"), load = column(h, "force_load_mean_y"),
             left  = column(h, "force_left_mean_y"),
             right = column(h, "force_right_mean_y"),
             defl  = column(h, "displacement_load_y");
  double imbalance = 0, asymmetry = 0, k_min = 1e300, k_max = 0;
  unsigned int rows = 0;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] > 1e-3)
    {
      imbalance = std::max(imbalance, std::abs(load[i] + left[i] + right[i]) / load[i]);
      asymmetry = std::max(asymmetry, std::abs(left[i] - right[i]) / load[i]);
      const double k = load[i] / -defl[i];
      k_min = std::min(k_min, k), k_max = std::max(k_max, k);
      ++rows;
    }
  std::cout << rows << " rows: imbalance " << imbalance << ", asymmetry " << asymmetry
            << ", secant stiffness " << k_min << " to " << k_max << " N/m" << std::endl;
  ASSERT_GT(rows, 10u);
  EXPECT_LT(imbalance, 0.02);
  EXPECT_LT(asymmetry, 0.01);
  EXPECT_LT(k_max / k_min, 1.05);
}

TEST(ThreePointBending, ServoHoldsTheCmodRate)
{
  // Under CMOD control the clip gauge opens at the CMOD rate: once the opening has
  // caught up with its target after the stroke's start-up ramp (by 1.6 ms), its rate
  // is within 5 % of the CMOD rate in every 0.25 ms window up to 3 ms.
  const std::string tag = "tpb_servo";
  const double rate     = 0.02;
  auto o                = coarse();
  o.push_back("Time/End time=0.003");
  lme_mpm_test::run_scene("three_point_bending.prm", tag, o);
  const auto h = lme_mpm_test::read_history(lme_mpm_test::scratch_path(tag));
  const auto t = column(h, "time"), w = column(h, "opening_cmod");
  double lo = 1e300, hi = 0;
  // Rows every 0.05 ms: windows of five rows.
  for (std::size_t i = 0; i + 5 < t.size(); ++i)
    if (t[i] >= 2e-3)
    {
      const double v = (w[i + 5] - w[i]) / (t[i + 5] - t[i]) / rate;
      lo = std::min(lo, v), hi = std::max(hi, v);
    }
  std::cout << "CMOD rate over 0.25 ms windows: " << lo << " to " << hi << " of " << rate
            << " m/s" << std::endl;
  ASSERT_LT(lo, hi);
  EXPECT_GT(lo, 0.95);
  EXPECT_LT(hi, 1.05);
}

TEST(ThreePointBending, RunsIn3D)
{
  // The beam as a 3D body 20 mm wide, rollers along its width: loaded, balanced and
  // symmetric after 0.8 ms, and its summary names the ligament's area b (D - a0).
  const std::string tag = "tpb_3d";
  const auto r          = lme_mpm_test::run_scene(
               "three_point_bending.prm", tag,
               {"Problem/Dimension=3", "Grid/Lower corner=0, 0, 0",
                "Grid/Upper corner=0.195, 0.075, 0.02", "Grid/Cell size=0.005",
                "Scene/three point bending/Width=0.02",
                "Scene/three point bending/Notch width=0.005",
                "Scene/three point bending/CMOD gauge length=0.015",
                "Scene/three point bending/Notch crack=false",
                "Scene/three point bending/Control=deflection", "Time/End time=0.0008",
                "Material 1/Fracture/Model=none"});
  EXPECT_DOUBLE_EQ(r.at("ligament_area"), 0.025 * 0.02);
  const auto h    = lme_mpm_test::read_history(lme_mpm_test::scratch_path(tag));
  const auto load = column(h, "force_load_mean_y"), left = column(h, "force_left_mean_y"),
             right = column(h, "force_right_mean_y");
  std::cout << "3D, last row: load " << load.back() << " N, supports " << left.back()
            << ", " << right.back() << " N" << std::endl;
  EXPECT_GT(load.back(), 10);
  EXPECT_LT(std::abs(load.back() + left.back() + right.back()) / load.back(), 0.05);
  EXPECT_LT(std::abs(left.back() - right.back()) / load.back(), 0.01);
}

TEST(ThreePointBending, BadInputNamesTheEntry)
{
  const std::string prm = lme_mpm_test::scene("three_point_bending.prm");
  const std::string dir = lme_mpm_test::scratch("tpb_bad");
  const auto error      = [&](const std::vector<std::string> &o)
  { return lme_mpm_test::run_error(prm, o, dir); };
  const std::string s = "Scene/three point bending/";
  for (const auto &c : std::vector<std::pair<std::string, std::string>>{
           {"Notch depth=0.05", "Notch depth"},
           {"Span=0.2", "Span"},
           {"CMOD gauge length=0.004", "CMOD gauge length"},
           {"CMOD gauge length=0.13", "CMOD gauge length"},
           {"Roller radius=0", "Roller radius"},
           {"Length=0.3", "Length"},
           {"Stop at load fraction=1", "Stop at load fraction"}})
  {
    const std::string message = error({s + c.first});
    EXPECT_NE(message.find(s + c.second), std::string::npos)
        << c.first << ": " << message;
  }
  // A servo rate set in Loading control that differs from the scene's is blamed on
  // both entries.
  const std::string m = error({"Loading control/Opening rate=0.05"});
  EXPECT_NE(m.find("Loading control/Opening rate"), std::string::npos) << m;
  EXPECT_NE(m.find(s + "CMOD rate"), std::string::npos) << m;
}
