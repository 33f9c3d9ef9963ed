#ifndef LME_MPM_TESTS_TEST_HELPERS_H
#define LME_MPM_TESTS_TEST_HELPERS_H

#include <lme_mpm/base/input.h>
#include <lme_mpm/simulation/run.h>
#include <lme_mpm/simulation/simulation.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
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
} // namespace lme_mpm_test

#endif
