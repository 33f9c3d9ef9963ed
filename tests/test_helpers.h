#ifndef LME_MPM_TESTS_TEST_HELPERS_H
#define LME_MPM_TESTS_TEST_HELPERS_H

#include <lme_mpm/base/input.h>
#include <lme_mpm/solver/simulation.h>

#include <unistd.h>

#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace lme_mpm_test
{
inline std::string scene(const std::string &name)
{
  return std::string(LME_MPM_SOURCE_DIR) + "/prm/" + name;
}

/// A fresh scratch directory for one test's output.
inline std::string scratch(const std::string &name)
{
  // The process id keeps tests that ctest runs side by side apart.
  const auto dir = std::filesystem::temp_directory_path() /
                   ("lme_mpm_test_" + std::to_string(::getpid()) + "_" + name);
  std::filesystem::remove_all(dir);
  return dir.string();
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
} // namespace lme_mpm_test

#endif
