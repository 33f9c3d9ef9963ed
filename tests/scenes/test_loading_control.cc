// The servo of "Loading control": an elastic block squeezed by a rigid platen
// (prm/rigid_indentation.prm with a flat platen and rollers under the block), its
// lateral expansion held to a rate; the same block at the platen's constant velocity;
// a resumed servo run; and the entries' messages.
#include <gtest/gtest.h>

#include "test_helpers.h"

#include <cmath>

namespace
{
constexpr double target_rate = 0.05; // m/s
constexpr double stroke      = 2.0;  // m/s, the platen's prescribed speed

std::vector<std::string> squeeze(const std::string &type)
{
  return {"Body 2/Shape=rectangle(0.005, 0.0205, 0.055, 0.03)",
          "Boundary conditions/Constraint 1/Components=y",
          "Contact/Seat rigid surfaces=true",
          "Output/Opening gauges=lateral: 0.0105, 0.01, 0.0495, 0.01",
          "Output/Output interval=2e-5",
          "Output/Write particle files=false",
          "Time/End time=1.6e-3",
          "Loading control/Type=" + type,
          "Loading control/Gauge=lateral",
          "Loading control/Opening rate=" + std::to_string(target_rate),
          "Loading control/Devices=roller"};
}
} // namespace

TEST(LoadingControl, ServoHoldsTheOpeningRateOfAnElasticBlock)
{
  const auto r = lme_mpm_test::run_scene("rigid_indentation.prm", "servo_block",
                                         squeeze("opening rate"));
  const auto h = lme_mpm_test::read_history(lme_mpm_test::scratch_path("servo_block"));
  const auto t = lme_mpm_test::column(h.first, "time");
  const auto w = lme_mpm_test::column(h.first, "opening_lateral");
  const auto v = lme_mpm_test::column(h.first, "device_velocity");
  const auto d = lme_mpm_test::column(h.first, "device_travel");
  const auto &rows = h.second;
  ASSERT_GT(rows.size(), 60u);
  // Over the last third of the run (five response times after the start): the
  // opening rate within 3 % of the target, over the third and over each sixth.
  const std::size_t n = rows.size() - 1, a = n - n / 3, m = n - n / 6;
  const auto rate = [&](const std::size_t i, const std::size_t j)
  { return (rows[j][w] - rows[i][w]) / (rows[j][t] - rows[i][t]); };
  EXPECT_NEAR(rate(a, n) / target_rate, 1.0, 0.03);
  EXPECT_NEAR(rate(a, m) / target_rate, 1.0, 0.03);
  EXPECT_NEAR(rate(m, n) / target_rate, 1.0, 0.03);
  // The device never outruns its stroke, and its travel is its velocity integrated.
  for (const auto &row : rows)
    EXPECT_LE(std::abs(row[v]), stroke * (1 + 1e-12));
  EXPECT_NEAR(r.at("control_device_travel"), rows.back()[d], 1e-12);
  EXPECT_GT(r.at("control_response_time"), 0);
  // Elastic: what the device puts in stays as strain energy (no work of fracture).
  EXPECT_LT(r.at("max_energy_drift"), 1e-2);
  EXPECT_NEAR(r.at("work_of_fracture") / r.at("final_strain_energy"), 0.0, 0.05);

  // At constant velocity, the gauge's gain (opening over travel) is the servo's:
  // the block is linear elastic, so the servo's travel for its final opening is the
  // one the constant-velocity run needed for it.
  lme_mpm_test::run_scene("rigid_indentation.prm", "servo_block_constant",
                          squeeze("constant velocity"));
  const auto c =
      lme_mpm_test::read_history(lme_mpm_test::scratch_path("servo_block_constant"));
  const auto cw              = lme_mpm_test::column(c.first, "opening_lateral");
  const auto cd              = lme_mpm_test::column(c.first, "displacement_roller_y");
  const double gain_constant = c.second.back()[cw] / -c.second.back()[cd];
  const double gain_servo    = rows.back()[w] / rows.back()[d];
  EXPECT_NEAR(gain_servo / gain_constant, 1.0, 0.1);
  EXPECT_GT(gain_constant, 0);
}

TEST(LoadingControl, ResumedServoRunEndsAlike)
{
  const std::string once  = lme_mpm_test::scratch("servo_once"),
                    twice = lme_mpm_test::scratch("servo_twice");
  auto sets               = squeeze("opening rate");
  sets.push_back("Time/End time=4e-4");
  sets.push_back("Output/Verbosity=0");
  std::vector<std::string> a = sets, b = sets;
  a.push_back("Output/Directory=" + once);
  b.push_back("Output/Directory=" + twice);
  b.push_back("Checkpoint/Every steps=700");
  std::ostringstream quiet;
  lme_mpm::run_parameter_file(lme_mpm_test::scene("rigid_indentation.prm"), a, quiet);
  lme_mpm_test::run_and_resume(lme_mpm_test::scene("rigid_indentation.prm"), b, twice);
  lme_mpm_test::expect_same_run(once, twice);
}

TEST(LoadingControl, EntriesAreCheckedAndNamed)
{
  const std::string prm = lme_mpm_test::scene("rigid_indentation.prm");
  const std::string out = lme_mpm_test::scratch("servo_bad");
  const auto error      = [&](std::vector<std::string> sets)
  { return lme_mpm_test::run_error(prm, sets, out); };
  auto base = squeeze("opening rate");
  auto with = [&](const std::string &s)
  {
    auto v = base;
    v.push_back(s);
    return error(v);
  };
  std::string m = with("Loading control/Gauge=cmod");
  EXPECT_NE(m.find("'Loading control/Gauge'"), std::string::npos) << m;
  EXPECT_NE(m.find("lateral"), std::string::npos) << m;
  m = with("Loading control/Devices=block");
  EXPECT_NE(m.find("'Loading control/Devices'"), std::string::npos) << m;
  EXPECT_NE(m.find("Prescribed velocity"), std::string::npos) << m;
  m = with("Loading control/Devices=platen");
  EXPECT_NE(m.find("no body is named 'platen'"), std::string::npos) << m;
  m = with("Loading control/Opening rate=0");
  EXPECT_NE(m.find("'Loading control/Opening rate'"), std::string::npos) << m;
  m = with("Output/Opening gauges=lateral: 0.0105, 0.01, 0.0495");
  EXPECT_NE(m.find("'Output/Opening gauges'"), std::string::npos) << m;
  EXPECT_NE(m.find("needs 4"), std::string::npos) << m;
  m = with("Output/Opening gauges=lateral: 0.0105, 0.03, 0.0495, 0.01");
  EXPECT_NE(m.find("no particle of a free body"), std::string::npos) << m;
  m = with("Output/Opening gauges=lateral: 0.0105, 0.01, 0.0106, 0.01");
  EXPECT_NE(m.find("more than twice its radius"), std::string::npos) << m;
  m = with("Output/Opening gauges=lateral: 0.0105, 0.01, 0.0495, 0.01, 0");
  EXPECT_NE(m.find("the radius of gauge 'lateral' must be positive"), std::string::npos)
      << m;
  m = with("Output/Opening gauges=lateral: 0.0105, 0.01, 0.0495, 0.01; lateral: 0.02, "
           "0.01, 0.03, 0.01");
  EXPECT_NE(m.find("two gauges are named 'lateral'"), std::string::npos) << m;
}
