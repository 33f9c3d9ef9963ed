// A run with a growing crack resumes bitwise identical.
#include <gtest/gtest.h>

#include "test_helpers.h"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>

namespace
{
using lme_mpm_test::checksum;
using lme_mpm_test::file_text;
using lme_mpm_test::with_settings;

/// Runs @p prm with @p settings to its end in @p dir; returns the run's results.
std::map<std::string, double> run(const std::string &prm,
                                  const std::vector<std::string> &settings,
                                  const std::string &dir)
{
  std::ostringstream quiet;
  return lme_mpm::run_parameter_file(prm, with_settings(settings, {}, dir), quiet);
}

/**
 * Runs @p prm with @p overrides (which write checkpoints into @p dir) to its end,
 * lets @p edit change the last checkpoint, and resumes from it in @p dir.
 */
void run_and_resume(const std::string &prm, const std::vector<std::string> &overrides,
                    const std::string &dir,
                    const std::function<void(const std::string &)> &edit = {})
{
  std::ostringstream quiet;
  lme_mpm::run_parameter_file(prm, overrides, quiet);
  ASSERT_TRUE(std::filesystem::exists(dir + "/checkpoint.bin"));
  if (edit)
    edit(dir + "/checkpoint.bin");
  lme_mpm::run_parameter_file(prm, overrides, quiet, dir);
}

/// The run in @p b ended in the state of the one in @p a, and wrote the same history.
void expect_same_run(const std::string &a, const std::string &b)
{
  EXPECT_FALSE(checksum(a).empty());
  EXPECT_EQ(checksum(a), checksum(b));
  EXPECT_EQ(file_text(a + "/history.csv"), file_text(b + "/history.csv"));
}
} // namespace

TEST(Checkpoint, GrowingCrackResumesBitwiseIdentical)
{
  // The coarse panel through crack initiation and growth; the last checkpoint falls
  // after the crack has started to grow, so the resumed run must rebuild the grown
  // crack and its second fields exactly. Linear shape functions keep it short under
  // the sanitizers.
  const std::vector<std::string> o = {"Shape functions/Type=linear",
                                      "Grid/Cell size=0.05",
                                      "Body 1/Holes=slot(0, 0.5, 0.25, 0.025, 0)",
                                      "Time/End time=22",
                                      "Output/Write particle files=false",
                                      "Output/Verbosity=0",
                                      "Checkpoint/Every steps=600"};
  const std::string prm            = lme_mpm_test::scene("mode_i_panel.prm");
  const std::string a              = lme_mpm_test::scratch("crack_ckpt_a"),
                    b              = lme_mpm_test::scratch("crack_ckpt_b");
  const auto full                  = run(prm, o, a);
  const std::string grown          = file_text(a + "/cracks.csv");
  EXPECT_GT(std::count(grown.begin(), grown.end(), '\n'), 4) << grown; // it grew
  EXPECT_GT(full.at("steps"), 1800);
  run_and_resume(prm, with_settings(o, {}, b), b);
  expect_same_run(a, b);
  EXPECT_EQ(grown, file_text(b + "/cracks.csv"));
}
