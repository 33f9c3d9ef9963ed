// A run with a growing crack resumes bitwise identical.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

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
using lme_mpm_test::expect_same_run;
using lme_mpm_test::file_text;
using lme_mpm_test::run_and_resume;
using lme_mpm_test::with_settings;

/// Runs @p prm with @p settings to its end in @p dir; returns the run's results.
std::map<std::string, double> run(const std::string &prm,
                                  const std::vector<std::string> &settings,
                                  const std::string &dir)
{
  std::ostringstream quiet;
  return lme_mpm::run_parameter_file(prm, with_settings(settings, {}, dir), quiet);
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

namespace
{
/// Runs the program with @p args (shell words), output to @p log; the exit code.
int run_binary(const std::string &args, const std::string &log)
{
  return WEXITSTATUS(std::system(
      (std::string(LME_MPM_BINARY) + " " + args + " > " + log + " 2>&1").c_str()));
}

nlohmann::json summary_of(const std::string &dir)
{
  return nlohmann::json::parse(file_text(dir + "/summary.json"));
}
} // namespace

TEST(Checkpoint, KilledRunResumesFromItsLastCheckpointToTheSameHistory)
{
  // SIGKILL leaves no last row and no checkpoint of its own: the run resumes from
  // its last periodic checkpoint, cuts the rows written after it, and writes them
  // again, byte for byte.
  const std::string out               = lme_mpm_test::scratch("killed");
  const std::string ref               = lme_mpm_test::scratch("killed_reference");
  const std::string log               = lme_mpm_test::scratch_path("killed.log");
  const std::vector<std::string> sets = {
      "Time/End time=0.6", "Output/Output interval=0.01",
      "Output/Write particle files=false", "Checkpoint/Every steps=4000"};
  auto in = [&](const std::string &dir)
  {
    auto s = sets;
    s.push_back("Output/Directory=" + dir);
    return s;
  };
  const int status = lme_mpm_test::run_and_signal(
      lme_mpm_test::scene("vibrating_bar.prm"), in(out), out, log, SIGKILL, 20, true);
  ASSERT_TRUE(WIFSIGNALED(status)) << lme_mpm_test::file_text(log);
  EXPECT_FALSE(std::filesystem::exists(out + "/summary.json"));
  EXPECT_EQ(run_binary("--threads 1 --resume " + out, log), 0)
      << lme_mpm_test::file_text(log);
  std::string args = lme_mpm_test::scene("vibrating_bar.prm") + " --threads 1";
  for (const auto &s2 : in(ref))
    args += " --set \"" + s2 + "\"";
  ASSERT_EQ(run_binary(args, log), 0) << lme_mpm_test::file_text(log);
  EXPECT_EQ(summary_of(out)["state_checksum"], summary_of(ref)["state_checksum"]);
  EXPECT_EQ(lme_mpm_test::file_text(out + "/history.csv"),
            lme_mpm_test::file_text(ref + "/history.csv"));
}
