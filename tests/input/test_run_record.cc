// What a run leaves behind about itself: parameters.prm and summary.json's "run"
// object (enough to redo it), --version and --print-parameters FILE, and a run ended
// by SIGINT that says so and can be continued.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "test_helpers.h"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <thread>

#include <sys/wait.h>
#include <unistd.h>

namespace
{
std::string bar()
{
  return lme_mpm_test::scene("vibrating_bar.prm");
}

/// Runs the program with @p args (shell words), output to @p log; the exit code.
int run(const std::string &args, const std::string &log)
{
  return WEXITSTATUS(std::system(
      (std::string(LME_MPM_BINARY) + " " + args + " > " + log + " 2>&1").c_str()));
}

nlohmann::json summary(const std::string &dir)
{
  return nlohmann::json::parse(lme_mpm_test::file_text(dir + "/summary.json"));
}
} // namespace

TEST(RunRecord, ParametersFileRedoesTheRunAndSummaryNamesTheCommand)
{
  const std::string a   = lme_mpm_test::scratch("record_a"),
                    b   = lme_mpm_test::scratch("record_b");
  const std::string log = lme_mpm_test::scratch_path("record.log");
  ASSERT_EQ(run(bar() +
                    " --threads 1 --set \"Time/End time=0.002\" --set "
                    "\"Output/Write particle files=false\" --set \"Output/Directory=" +
                    a + "\"",
                log),
            0)
      << lme_mpm_test::file_text(log);
  ASSERT_TRUE(std::filesystem::exists(a + "/parameters.prm"));
  const auto first = summary(a);
  EXPECT_EQ(first["run"]["overrides"].size(), 3u);
  EXPECT_NE(first["run"]["command_line"].get<std::string>().find("--threads 1"),
            std::string::npos);
  EXPECT_EQ(first["run"]["parameter_file"], bar());
  EXPECT_FALSE(first["run"]["version"].get<std::string>().empty());
  // The recorded file alone, with only the directory changed, gives the same bits.
  ASSERT_EQ(
      run(a + "/parameters.prm --threads 1 --set \"Output/Directory=" + b + "\"", log), 0)
      << lme_mpm_test::file_text(log);
  EXPECT_EQ(summary(b)["state_checksum"], first["state_checksum"]);
  EXPECT_EQ(summary(b)["steps"], first["steps"]);
}

TEST(RunRecord, VersionAndParametersOfAFile)
{
  const std::string log = lme_mpm_test::scratch_path("version.log");
  ASSERT_EQ(run("--version", log), 0);
  EXPECT_EQ(lme_mpm_test::file_text(log).rfind("lme-mpm ", 0), 0u);
  ASSERT_EQ(run("--print-parameters " + bar() + " --set \"Time/CFL=0.123\"", log), 0);
  const std::string text = lme_mpm_test::file_text(log);
  // The file's own value and the --set one, where the defaults have others.
  EXPECT_NE(text.find("= 0.123"), std::string::npos);
  EXPECT_NE(text.find("= rectangle(0, 0, 1, 0.1)"), std::string::npos);
}

TEST(RunRecord, InterruptedRunSaysSoAndResumesToTheSameHistory)
{
  // A run long enough to be interrupted: SIGINT once history.csv has rows. About
  // 17,000 steps, a second on one thread.
  const std::string out               = lme_mpm_test::scratch("interrupt");
  const std::string ref               = lme_mpm_test::scratch("interrupt_reference");
  const std::string log               = lme_mpm_test::scratch_path("interrupt.log");
  const std::vector<std::string> sets = {
      "Time/End time=0.4", "Output/Output interval=0.01",
      "Output/Write particle files=false", "Checkpoint/Every steps=1000000"};
  auto in = [&](const std::string &dir)
  {
    auto s = sets;
    s.push_back("Output/Directory=" + dir);
    return s;
  };
  const int status =
      lme_mpm_test::run_and_signal(bar(), in(out), out, log, SIGINT, 3, false);
  ASSERT_TRUE(WIFEXITED(status)) << lme_mpm_test::file_text(log);
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGINT);
  const auto s = summary(out);
  EXPECT_EQ(s["status"], "interrupted");
  const std::string message = s["message"];
  EXPECT_NE(message.find("Interrupted by SIGINT"), std::string::npos) << message;
  EXPECT_NE(message.find("--resume " + out), std::string::npos) << message;
  EXPECT_NE(lme_mpm_test::file_text(log).find("Interrupted by SIGINT"),
            std::string::npos);
  ASSERT_TRUE(std::filesystem::exists(out + "/checkpoint.bin"));
  // It continues from there to the end with the parameters it recorded, the
  // directory alone on the command line (the interrupted step's extra row goes).
  EXPECT_EQ(run("--threads 1 --resume " + out, log), 0) << lme_mpm_test::file_text(log);
  EXPECT_EQ(summary(out)["status"], "completed");
  std::string args = bar() + " --threads 1";
  for (const auto &s2 : in(ref))
    args += " --set \"" + s2 + "\"";
  ASSERT_EQ(run(args, log), 0) << lme_mpm_test::file_text(log);
  EXPECT_EQ(summary(out)["state_checksum"], summary(ref)["state_checksum"]);
  EXPECT_EQ(lme_mpm_test::file_text(out + "/history.csv"),
            lme_mpm_test::file_text(ref + "/history.csv"));
}
