#ifndef LME_MPM_TESTS_TEST_HELPERS_H
#define LME_MPM_TESTS_TEST_HELPERS_H

#include <lme_mpm/base/input.h>
#include <lme_mpm/simulation/run.h>
#include <lme_mpm/simulation/simulation.h>

#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace lme_mpm_test
{
inline std::string scene(const std::string &name)
{
  return std::string(LME_MPM_SOURCE_DIR) + "/prm/" + name;
}

/// The scratch directory of one test's output (see scratch()).
inline std::string scratch_path(const std::string &name)
{
  // The process id keeps tests that ctest runs side by side apart.
  return (std::filesystem::temp_directory_path() /
          ("lme_mpm_test_" + std::to_string(::getpid()) + "_" + name))
      .string();
}

/// A fresh (emptied) scratch directory for one test's output.
inline std::string scratch(const std::string &name)
{
  const std::string dir = scratch_path(name);
  std::filesystem::remove_all(dir);
  return dir;
}

inline std::string file_text(const std::string &path)
{
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// extra, then the scene's settings, then the output directory.
inline std::vector<std::string> with_settings(const std::vector<std::string> &scene,
                                              std::vector<std::string> extra,
                                              const std::string &dir)
{
  extra.insert(extra.end(), scene.begin(), scene.end());
  extra.push_back("Output/Directory=" + dir);
  return extra;
}

/// The state checksum a run wrote to summary.json ("" if none).
inline std::string checksum(const std::string &dir)
{
  const std::string s = file_text(dir + "/summary.json");
  const auto pos      = s.find("\"state_checksum\": \"");
  return pos == std::string::npos ? "" : s.substr(pos + 19, 16);
}

/// history.csv of an output directory: the column names and the rows.
inline std::pair<std::vector<std::string>, std::vector<std::vector<double>>>
read_history(const std::string &dir)
{
  std::ifstream in(dir + "/history.csv");
  std::string line;
  std::getline(in, line);
  std::pair<std::vector<std::string>, std::vector<std::vector<double>>> h;
  h.first = lme_mpm::input::split(line, ',');
  while (std::getline(in, line))
    h.second.push_back(lme_mpm::input::parse_doubles(line, dir + "/history.csv"));
  return h;
}

/// The index of the column @p name among @p names; throws if there is none.
inline std::size_t column(const std::vector<std::string> &names, const std::string &name)
{
  const auto c = std::find(names.begin(), names.end(), name);
  if (c == names.end())
    throw std::runtime_error("history.csv has no column '" + name + "'");
  return c - names.begin();
}

/// Runs a scene quietly with overrides; output into a scratch directory.
inline std::map<std::string, double> run_scene(const std::string &prm,
                                               const std::string &tag,
                                               std::vector<std::string> overrides = {})
{
  overrides.push_back("Output/Directory=" + scratch(tag));
  overrides.push_back("Output/Verbosity=0");
  std::ostringstream quiet;
  return lme_mpm::run_parameter_file(scene(prm), overrides, quiet);
}

/// The message of the exception a run throws ("" if none).
inline std::string run_error(const std::string &prm, std::vector<std::string> overrides,
                             const std::string &out_dir)
{
  overrides.push_back("Output/Directory=" + out_dir);
  overrides.push_back("Output/Verbosity=0");
  try
  {
    std::ostringstream quiet;
    lme_mpm::run_parameter_file(prm, overrides, quiet);
  }
  catch (const std::exception &e)
  {
    return lme_mpm::input::concise_message(e);
  }
  return "";
}

/**
 * Runs @p prm with @p overrides (which write checkpoints into @p dir) to its end, then
 * resumes in @p dir from its last checkpoint before the end (checkpoint.bin.prev: a
 * finished run also keeps one of its last step, checkpoint.bin), after @p edit has
 * changed that checkpoint.
 */
inline void run_and_resume(const std::string &prm,
                           const std::vector<std::string> &overrides,
                           const std::string &dir,
                           const std::function<void(const std::string &)> &edit = {})
{
  std::ostringstream quiet;
  lme_mpm::run_parameter_file(prm, overrides, quiet);
  ASSERT_TRUE(std::filesystem::exists(dir + "/checkpoint.bin.prev"));
  std::filesystem::rename(dir + "/checkpoint.bin.prev", dir + "/checkpoint.bin");
  if (edit)
    edit(dir + "/checkpoint.bin");
  lme_mpm::run_parameter_file(prm, overrides, quiet, dir);
}

/// The run in @p b ended in the state of the one in @p a, and wrote the same history.
inline void expect_same_run(const std::string &a, const std::string &b)
{
  EXPECT_FALSE(checksum(a).empty());
  EXPECT_EQ(checksum(a), checksum(b));
  EXPECT_EQ(file_text(a + "/history.csv"), file_text(b + "/history.csv"));
}
#ifdef LME_MPM_BINARY
/**
 * Starts the program on @p prm with @p sets (shell-free argv), output to @p log;
 * sends @p signal once history.csv in @p out has @p rows rows (and, with
 * @p checkpoint, once a checkpoint exists); returns the wait status.
 */
inline int run_and_signal(const std::string &prm, const std::vector<std::string> &sets,
                          const std::string &out, const std::string &log,
                          const int signal, const std::size_t rows, const bool checkpoint)
{
  const pid_t pid = fork();
  if (pid < 0)
    return -1;
  if (pid == 0)
  {
    if (!std::freopen(log.c_str(), "w", stdout) ||
        !std::freopen(log.c_str(), "a", stderr))
      _exit(99);
    std::vector<std::string> args = {LME_MPM_BINARY, prm, "--threads", "1"};
    for (const auto &s : sets)
      args.push_back("--set"), args.push_back(s);
    std::vector<char *> argv;
    for (auto &a : args)
      argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    _exit(98);
  }
  const auto ready = [&]()
  {
    // Lines counted, not parsed: the run may be writing one.
    const std::string text = file_text(out + "/history.csv");
    return std::size_t(std::count(text.begin(), text.end(), '\n')) > rows &&
           (!checkpoint || std::filesystem::exists(out + "/checkpoint.bin"));
  };
  for (int i = 0; i < 1200 && !ready(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
  kill(pid, signal);
  int status = 0;
  waitpid(pid, &status, 0);
  return status;
}
#endif
} // namespace lme_mpm_test

#endif
