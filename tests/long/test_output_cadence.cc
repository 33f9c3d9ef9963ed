// What a run reports does not depend on how often it writes: peaks, their times,
// stop rules and the energy drift are checked every step.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "test_helpers.h"

#include <string>
#include <vector>

namespace
{
/// summary.json of the run of @p prm with @p settings and history rows every
/// @p interval seconds.
nlohmann::json run_with_interval(const std::string &prm, const std::string &tag,
                                 std::vector<std::string> settings,
                                 const std::string &interval)
{
  settings.push_back("Output/Output interval=" + interval);
  settings.push_back("Output/Write particle files=false");
  lme_mpm_test::run_scene(prm, tag, settings);
  return nlohmann::json::parse(
      lme_mpm_test::file_text(lme_mpm_test::scratch_path(tag) + "/summary.json"));
}

/// Every value of @p a equals @p b's, but those that time or weigh the run itself.
void expect_same_results(const nlohmann::json &a, const nlohmann::json &b)
{
  for (const auto &[key, value] : a.items())
  {
    if (key == "run" || key == "wall_seconds" || key == "particle_steps_per_second" ||
        key == "peak_resident_megabytes" || key.rfind("stage_seconds_", 0) == 0)
      continue;
    ASSERT_TRUE(b.contains(key)) << key;
    EXPECT_EQ(value, b[key]) << key;
  }
}
} // namespace

TEST(Output, ResultsDoNotDependOnTheOutputCadence)
{
  // A coarse Brazilian disc loaded fast enough to split in 1.3 ms: its stop rule
  // (the load below 0.7 of its peak) at the same step, the same peak and the same
  // dissipated energy there, with rows every 10 us and every 43 us (before, the stop
  // and the peak were judged on the rows: 3,153 against 3,281 steps and 69 against
  // 113 J).
  const std::vector<std::string> disc = {"Grid/Cell size=0.005",
                                         "Scene/brazilian/Loading velocity=0.25",
                                         "Time/End time=1.6e-3"};
  const auto dense  = run_with_interval("brazilian.prm", "cadence_a", disc, "1e-5");
  const auto sparse = run_with_interval("brazilian.prm", "cadence_b", disc, "4.3e-5");
  EXPECT_EQ(dense["status"], "stopped");
  EXPECT_GT(dense["dissipated_energy"].get<double>(), 0);
  expect_same_results(dense, sparse);
  // The drop weight's peaks, their times and the crack's and softening front's speeds.
  const std::vector<std::string> beam = {
      "Grid/Step sizes x=92*0.005", "Grid/Step sizes y=37*0.005",
      "Scene/drop weight/Notch width=0.005", "Time/End time=2.5e-4"};
  const auto a = run_with_interval("drop_weight.prm", "cadence_c", beam, "5e-6");
  const auto b = run_with_interval("drop_weight.prm", "cadence_d", beam, "2.3e-5");
  EXPECT_GT(a["peak_impact_force"].get<double>(), 0);
  EXPECT_GT(a["time_of_peak_reaction_force"].get<double>(), 0);
  expect_same_results(a, b);
}
