// A full disk: every file a run writes either holds its old or its new contents, a
// failed write names the file and the system's reason, and a checkpoint that cannot
// be completed leaves the previous one to resume from. The failure is injected with
// the per-file size limit (RLIMIT_FSIZE, EFBIG "File too large"), which every
// machine allows; doc/outputs.md shows the same on a full file system (ENOSPC).
#include <gtest/gtest.h>

#include "test_helpers.h"

#include <nlohmann/json.hpp>
#include <sys/resource.h>

#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace
{
using lme_mpm_test::checksum;
using lme_mpm_test::file_text;
using lme_mpm_test::with_settings;

/// Files larger than @p bytes cannot be written while it lives.
class FileSizeLimit
{
public:
  explicit FileSizeLimit(const rlim_t bytes)
  {
    getrlimit(RLIMIT_FSIZE, &saved);
    // Without this the kernel ends the process (SIGXFSZ) instead of failing the write.
    previous       = std::signal(SIGXFSZ, SIG_IGN);
    rlimit limit   = saved;
    limit.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &limit);
  }
  ~FileSizeLimit()
  {
    setrlimit(RLIMIT_FSIZE, &saved);
    std::signal(SIGXFSZ, previous);
  }

private:
  rlimit saved{};
  void (*previous)(int) = nullptr;
};

// The tension bar with eigensoftening, about 1,900 steps.
const std::vector<std::string> bar = {"Output/Verbosity=0", "Output/Output interval=2e-5",
                                      "Time/End time=4e-4"};

std::string prm()
{
  return lme_mpm_test::scene("tension_bar.prm");
}

/// The message of the run's error ("" if it ran through).
std::string run(const std::vector<std::string> &settings, const std::string &dir,
                const std::string &resume = "")
{
  try
  {
    std::ostringstream quiet;
    lme_mpm::run_parameter_file(prm(), with_settings(settings, bar, dir), quiet, resume);
  }
  catch (const std::exception &e)
  {
    return lme_mpm::input::concise_message(e);
  }
  return "";
}

std::vector<std::string> temporary_files(const std::string &dir)
{
  std::vector<std::string> tmp;
  for (const auto &f : std::filesystem::directory_iterator(dir))
    if (f.path().extension() == ".tmp")
      tmp.push_back(f.path().filename().string());
  return tmp;
}

/// summary.json is absent, or valid JSON of an aborted run whose message has @p file.
void expect_aborted_or_absent(const std::string &dir, const std::string &file)
{
  if (!std::filesystem::exists(dir + "/summary.json"))
    return;
  nlohmann::json j;
  ASSERT_NO_THROW(j = nlohmann::json::parse(file_text(dir + "/summary.json")));
  EXPECT_EQ(j.at("status"), "aborted");
  EXPECT_NE(j.at("message").get<std::string>().find(file), std::string::npos)
      << j.at("message");
}

std::uintmax_t file_size(const std::string &path)
{
  return std::filesystem::file_size(path);
}

/// The first @p n lines of @p text.
std::string first_lines(const std::string &text, const unsigned int n)
{
  std::size_t end = 0;
  for (unsigned int i = 0; i < n && end < text.size(); ++i)
    end = text.find('\n', end) + 1;
  return text.substr(0, end);
}
} // namespace

TEST(FullDisk, AFailedRowNamesTheFileAndLeavesWholeRows)
{
  // A row every step: history.csv outgrows every other file of the run (the largest,
  // parameters.prm, is written first and must fit).
  const std::vector<std::string> rows = {"Output/Output interval=1e-7"};
  const std::string a                 = lme_mpm_test::scratch("disk_row_a"),
                    b                 = lme_mpm_test::scratch("disk_row_b");
  ASSERT_EQ(run(rows, a), "");
  const std::string history = file_text(a + "/history.csv");
  const auto limit =
      std::max(file_size(a + "/parameters.prm"), file_size(a + "/damage.csv")) + 2000;
  ASSERT_GT(history.size(), limit + 2000);
  std::string kept;
  for (unsigned int n = 1; first_lines(history, n).size() <= limit; ++n)
    kept = first_lines(history, n);
  std::string message;
  {
    FileSizeLimit limited(limit);
    message = run(rows, b);
  }
  EXPECT_NE(message.find("cannot write '" + b + "/history.csv'"), std::string::npos)
      << message;
  EXPECT_NE(message.find(std::strerror(EFBIG)), std::string::npos) << message;
  // The row that did not fit was cut off again.
  EXPECT_EQ(file_text(b + "/history.csv"), kept);
  EXPECT_TRUE(temporary_files(b).empty());
  ASSERT_TRUE(std::filesystem::exists(b + "/summary.json"));
  expect_aborted_or_absent(b, "history.csv");
}

TEST(FullDisk, AFailedParticleFileIsNamedAndTheSummaryStaysValid)
{
  // A finer bar whose particle files outgrow the limit after the first one.
  const std::vector<std::string> fine = {"Grid/Cell size=0.0005", "Time/End time=4e-5",
                                         "Output/Output interval=1e-5",
                                         "Output/Write particle files=true"};
  const std::string a                 = lme_mpm_test::scratch("disk_vtu_a"),
                    b                 = lme_mpm_test::scratch("disk_vtu_b");
  ASSERT_EQ(run(fine, a), "");
  const auto limit = file_size(a + "/parameters.prm") + 20000;
  std::string too_large;
  for (unsigned int n = 0; too_large.empty(); ++n)
  {
    const std::string name = "particles_0000" + std::to_string(n) + ".vtu";
    ASSERT_TRUE(std::filesystem::exists(a + "/" + name)) << "no file above the limit";
    if (file_size(a + "/" + name) > limit)
      too_large = name;
  }
  ASSERT_NE(too_large, "particles_00000.vtu"); // the run is under way when it fails
  std::string message;
  {
    FileSizeLimit limited(limit);
    message = run(fine, b);
  }
  EXPECT_NE(message.find("cannot write '" + b + "/" + too_large + "'"), std::string::npos)
      << message;
  EXPECT_NE(message.find(std::strerror(EFBIG)), std::string::npos) << message;
  EXPECT_FALSE(std::filesystem::exists(b + "/" + too_large));
  EXPECT_TRUE(std::filesystem::exists(b + "/particles_00000.vtu"));
  EXPECT_TRUE(temporary_files(b).empty());
  ASSERT_TRUE(std::filesystem::exists(b + "/summary.json"));
  expect_aborted_or_absent(b, too_large);
}

TEST(FullDisk, AFailedCheckpointKeepsThePreviousOneToResumeFrom)
{
  const std::string a                        = lme_mpm_test::scratch("disk_ckpt_a"),
                    b                        = lme_mpm_test::scratch("disk_ckpt_b");
  const std::vector<std::string> quiet_files = {"Output/Write particle files=false",
                                                "Checkpoint/Every steps=300"};
  ASSERT_EQ(run(quiet_files, a), "");
  // A run that stops at the first checkpoint, then goes on from it with too little
  // room for the next one.
  auto first = quiet_files;
  first.push_back("Time/Maximum steps=300");
  ASSERT_EQ(run(first, b), "");
  const std::string kept = file_text(b + "/checkpoint.bin");
  ASSERT_GT(kept.size(), file_size(b + "/parameters.prm") + 2000);
  std::string message;
  {
    FileSizeLimit limit(kept.size() - 1000);
    message = run(quiet_files, b, b);
  }
  EXPECT_NE(message.find("cannot write '" + b + "/checkpoint.bin'"), std::string::npos)
      << message;
  EXPECT_NE(message.find(std::strerror(EFBIG)), std::string::npos) << message;
  EXPECT_EQ(file_text(b + "/checkpoint.bin"), kept);
  EXPECT_TRUE(temporary_files(b).empty());
  expect_aborted_or_absent(b, "checkpoint.bin");
  // With room again the run goes on from the checkpoint that was kept and ends as the
  // uninterrupted one.
  ASSERT_EQ(run(quiet_files, b, b), "");
  EXPECT_FALSE(checksum(a).empty());
  EXPECT_EQ(checksum(a), checksum(b));
  EXPECT_EQ(file_text(a + "/history.csv"), file_text(b + "/history.csv"));
}
