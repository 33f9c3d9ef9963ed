// Drop-weight impact (prm/drop_weight.prm) on a coarse uniform grid, over the first
// 0.15 ms: the hammer starts with the kinetic energy of 120.6 kg at 2.64 m/s, the
// impact force the contact reports is the rate of change of the hammer's momentum,
// the supports feel nothing before the stress wave can have reached them, the energy
// balance closes and the summary gives the peaks in order; a resumed run reports
// what the uninterrupted one does; the scene's input checks name their entries.
#include <gtest/gtest.h>

#include "test_helpers.h"

#include <cmath>
#include <map>
#include <sstream>

namespace
{
/// 5 mm cells everywhere (particles 2.5 mm apart, so the notch is widened to 5 mm).
std::vector<std::string> coarse()
{
  return {"Grid/Step sizes x=92*0.005", "Grid/Step sizes y=37*0.005",
          "Scene/drop weight/Notch width=0.005", "Time/End time=1.5e-4"};
}
} // namespace

TEST(DropWeight, ImpactForceIsTheHammersMomentumRateAndTheSupportsWaitForTheWave)
{
  const std::string tag = "drop_weight_coarse";
  const auto r          = lme_mpm_test::run_scene("drop_weight.prm", tag, coarse());
  const auto h          = lme_mpm_test::read_history(lme_mpm_test::scratch_path(tag));
  const auto col        = [&](const std::string &name)
  { return lme_mpm_test::column(h.first, name); };
  const std::size_t t = col("time"), impact = col("impact_force"),
                    rate = col("hammer_momentum_rate"), reaction = col("reaction_force"),
                    kinetic = col("kinetic_energy");
  // The hammer's mass per thickness times the thickness is 120.6 kg (its density comes
  // from the scene): at t = 0 only it moves.
  EXPECT_NEAR(h.second.front()[kinetic], 0.5 * 120.6 * 2.64 * 2.64, 1e-9 * 420);
  const double peak = r.at("peak_impact_force");
  ASSERT_GT(peak, 0);
  // The impulse the contact reports against the hammer's momentum change, row by
  // row summed: the projected exchange gives the particles each step's impulse in
  // that step, so the sums agree to the history's round-off (the nodal exchange,
  // which the particles saw half in one step and half in the next, differed by
  // 0.3 % of the impulse).
  double impulse = 0, momentum_change = 0, worst = 0, early = 0;
  for (std::size_t i = 1; i < h.second.size(); ++i)
  {
    const auto &row   = h.second[i];
    const double span = row[t] - h.second[i - 1][t];
    impulse += row[impact] * span;
    momentum_change += row[rate] * span;
    worst = std::max(worst, std::abs(impulse - momentum_change));
    // The nearest support is 0.1 m down and 0.115 m across from the hammer's edge:
    // 41 us at the plane-stress wave speed, 3.69 km/s.
    if (row[t] < 3e-5)
      early = std::max(early, std::abs(row[reaction]));
  }
  std::cout << "peak impact " << peak << " N at " << r.at("time_of_peak_impact_force")
            << " s, peak reaction " << r.at("peak_reaction_force") << " N at "
            << r.at("time_of_peak_reaction_force") << " s; impulse " << impulse
            << " N s, largest difference from the hammer's momentum change " << worst
            << " N s, largest reaction before 30 us " << early << " N, energy drift "
            << r.at("max_energy_drift") << std::endl;
  EXPECT_LT(worst, 1e-6 * impulse);
  EXPECT_LT(early, 1e-3 * peak);
  EXPECT_GT(r.at("peak_reaction_force"), 0);
  EXPECT_LT(r.at("time_of_peak_impact_force"), r.at("time_of_peak_reaction_force"));
  EXPECT_LT(r.at("max_energy_drift"), 0.005);
}

TEST(DropWeight, SingleFieldSupportsTakeWhatTheBeamAndHammerLose)
{
  // The paper's set-up: hammer and beam on one velocity field, the supports node sets
  // with zero vertical velocity. The only vertical impulse the particles receive is
  // the supports' (their reactions averaged over each step's ends, as the update
  // averages the accelerations), so the hammer's and the beam's momentum changes add
  // up to it to round-off, row by row.
  const std::string tag = "drop_weight_single_field";
  const auto r   = lme_mpm_test::run_scene("drop_weight_single_field.prm", tag, coarse());
  const auto h   = lme_mpm_test::read_history(lme_mpm_test::scratch_path(tag));
  const auto col = [&](const std::string &name)
  { return lme_mpm_test::column(h.first, name); };
  const std::size_t t = col("time"), impact = col("impact_force"),
                    hammer = col("hammer_momentum_rate"),
                    beam = col("beam_momentum_rate"), reaction = col("reaction_force");
  double support = 0, worst = 0, early = 0;
  for (std::size_t i = 1; i < h.second.size(); ++i)
  {
    const auto &row   = h.second[i];
    const double span = row[t] - h.second[i - 1][t];
    EXPECT_EQ(row[impact], row[hammer]);
    support += row[reaction] * span;
    worst = std::max(worst, std::abs((row[hammer] + row[beam] - row[reaction]) * span));
    if (row[t] < 3e-5)
      early = std::max(early, std::abs(row[reaction]));
  }
  const double peak = r.at("peak_impact_force");
  std::cout << "single field: peak impact " << peak << " N at "
            << r.at("time_of_peak_impact_force") << " s, peak reaction "
            << r.at("peak_reaction_force") << " N at "
            << r.at("time_of_peak_reaction_force") << " s; supports' impulse " << support
            << " N s, largest row imbalance " << worst << " N s, largest reaction before "
            << "30 us " << early << " N, energy drift " << r.at("max_energy_drift")
            << std::endl;
  ASSERT_GT(peak, 0);
  ASSERT_GT(support, 0);
  EXPECT_LT(worst, 1e-9 * 120.6 * 2.64);
  EXPECT_LT(early, 1e-3 * peak);
  EXPECT_LT(r.at("time_of_peak_impact_force"), r.at("time_of_peak_reaction_force"));
  EXPECT_LT(r.at("max_energy_drift"), 0.005);
}

TEST(DropWeight, ResumedRunReportsWhatTheUninterruptedOneDoes)
{
  // The scene's peaks and the hammer's momentum rate come from its history rows; a
  // checkpoint keeps what the rows have seen, so a run resumed from step 200 of 246
  // writes the same history and the same peaks as the run without the break.
  std::ostringstream quiet;
  const std::string prm = lme_mpm_test::scene("drop_weight.prm");
  std::map<std::string, double> results[2];
  std::string dirs[2];
  for (int resume : {0, 1})
  {
    dirs[resume] =
        lme_mpm_test::scratch(resume ? "drop_weight_resume" : "drop_weight_full");
    auto o = coarse();
    o.push_back("Time/End time=1e-4");
    o.push_back("Checkpoint/Every steps=100");
    o.push_back("Output/Directory=" + dirs[resume]);
    o.push_back("Output/Verbosity=0");
    results[resume] = lme_mpm::run_parameter_file(prm, o, quiet);
    if (resume)
      results[resume] = lme_mpm::run_parameter_file(prm, o, quiet, dirs[resume]);
  }
  for (const std::string key : {"peak_impact_force", "time_of_peak_impact_force",
                                "peak_reaction_force", "time_of_peak_reaction_force"})
    EXPECT_EQ(results[0].at(key), results[1].at(key)) << key;
  EXPECT_EQ(lme_mpm_test::file_text(dirs[0] + "/history.csv"),
            lme_mpm_test::file_text(dirs[1] + "/history.csv"));
}

TEST(DropWeight, BadInputNamesTheEntry)
{
  const std::string prm = lme_mpm_test::scene("drop_weight.prm");
  const std::string dir = lme_mpm_test::scratch("drop_weight_bad");
  const auto error      = [&](const std::vector<std::string> &o)
  { return lme_mpm_test::run_error(prm, o, dir); };
  EXPECT_NE(
      error({"Scene/drop weight/Notch depth=0.1"}).find("Scene/drop weight/Notch depth"),
      std::string::npos);
  EXPECT_NE(error({"Scene/drop weight/Span=0.5"}).find("Scene/drop weight/Span"),
            std::string::npos);
  EXPECT_NE(error({"Scene/drop weight/Impact velocity=0"})
                .find("Scene/drop weight/Impact velocity"),
            std::string::npos);
  EXPECT_NE(
      error({"Scene/drop weight/Hammer mass=-1"}).find("Scene/drop weight/Hammer mass"),
      std::string::npos);
  EXPECT_NE(error({"Scene/drop weight/Supports=left"}).find("Scene/drop weight/Supports"),
            std::string::npos);
  EXPECT_NE(error({"Scene/drop weight/Hammer=striker"}).find("Scene/drop weight/Hammer"),
            std::string::npos);
  // On one velocity field the supports are node sets: bodies of their names are
  // refused, naming the entry and what it needs.
  const std::string field = error({"Contact/Type=none"});
  EXPECT_NE(field.find("Scene/drop weight/Supports"), std::string::npos) << field;
  EXPECT_NE(field.find("Contact/Type = none"), std::string::npos) << field;
  // The hammer's density is the scene's: a density in the file is refused, naming it.
  const std::string density = error({"Material 2/Density=7800"});
  EXPECT_NE(density.find("Material 2/Density"), std::string::npos) << density;
  EXPECT_NE(density.find("Scene/drop weight/Hammer mass"), std::string::npos) << density;
  const std::string velocity =
      error({"Body 2/Initial velocity/Function expression=0; -1"});
  EXPECT_NE(velocity.find("Scene/drop weight/Impact velocity"), std::string::npos)
      << velocity;
}

TEST(DropWeight, NeighbourhoodCheckLooksOnlyAtTheCellsTheBeamStartsIn)
{
  // The scene's graded grid has empty cells 5 mm x 1.25 mm (coarse columns crossing
  // the rows of the hammer face), where C_eps = 1.5 would not reach the next particle
  // (2.5 mm away for 1.875 mm); the beam's own cells need only C_eps >= 1.
  const std::string tag = "drop_weight_eps";
  const auto r          = lme_mpm_test::run_scene(
               "drop_weight.prm", tag,
               {"Material 1/Fracture/Epsilon factor=1.5", "Time/End time=2e-7"});
  EXPECT_EQ(r.at("particles"), 24680);
  const std::string error = lme_mpm_test::run_error(
      lme_mpm_test::scene("drop_weight.prm"), {"Material 1/Fracture/Epsilon factor=0.9"},
      lme_mpm_test::scratch("drop_weight_eps_bad"));
  EXPECT_NE(error.find("Material 1/Fracture/Epsilon factor"), std::string::npos) << error;
}
