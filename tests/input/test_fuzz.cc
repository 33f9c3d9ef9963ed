// Fuzzing the input: random single-entry edits of the shipped scenes. Every run must
// either advance cleanly or stop with a message naming an entry; never crash, hang,
// exit 0 after an error or report 'completed' for a run that did nothing.
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/parameter_handler.h>

#include <gtest/gtest.h>

#include <lme_mpm/base/input.h>
#include <lme_mpm/simulation/run.h>
#include <lme_mpm/simulation/simulation.h>
#include <lme_mpm/solver/run_parameters.h>

#include <nlohmann/json.hpp>

#include "test_helpers.h"

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

namespace
{
struct Entry
{
  std::string path;    ///< "Subsection/Entry"
  std::string pattern; ///< deal.II's pattern description
  std::string value;   ///< the scene's value
};

/// deal.II mangles names in its JSON output ("Cell_20size"): undo it.
std::string demangle(const std::string &s)
{
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s[i] == '_' && i + 2 < s.size() + 0 && std::isxdigit(s[i + 1]) &&
        std::isxdigit(s[i + 2]))
    {
      out += static_cast<char>(std::stoi(s.substr(i + 1, 2), nullptr, 16));
      i += 2;
    }
    else
      out += s[i];
  return out;
}

void collect(const nlohmann::json &node, const std::string &prefix,
             std::vector<Entry> &entries)
{
  for (auto it = node.begin(); it != node.end(); ++it)
  {
    if (!it->is_object())
      continue;
    const std::string name = demangle(it.key());
    if (it->contains("value") && it->contains("pattern_description"))
      entries.push_back({prefix + name, (*it)["pattern_description"].get<std::string>(),
                         (*it)["value"].get<std::string>()});
    else
      collect(*it, prefix + name + "/", entries);
  }
}

/// Every entry of a scene, with the scene's values.
std::vector<Entry> scene_entries(const std::string &file)
{
  using namespace lme_mpm;
  ParameterCounts counts;
  {
    ParameterHandler prm;
    ParameterCounts::declare_parameters(prm);
    prm.parse_input(file, "", true, false);
    counts.parse_parameters(prm);
  }
  ParameterHandler prm;
  if (counts.dim == 2)
    Simulation<2>::declare_parameters(prm, counts);
  else
    Simulation<3>::declare_parameters(prm, counts);
  prm.parse_input(file);
  std::stringstream json;
  prm.print_parameters(json, ParameterHandler::JSON);
  std::vector<Entry> entries;
  collect(nlohmann::json::parse(json.str()), "", entries);
  return entries;
}

/// A random value of the entry's type, extremes included.
std::string random_value(const Entry &e, std::mt19937 &rng)
{
  const auto pick = [&](const std::vector<std::string> &v)
  { return v[std::uniform_int_distribution<std::size_t>(0, v.size() - 1)(rng)]; };
  const std::string &p = e.pattern;
  if (p.rfind("[Double", 0) == 0)
  {
    double current = 1;
    try
    {
      current = std::stod(e.value);
    }
    catch (...)
    {
    }
    return pick({"0", "-1", "1e-300", "1e300", "1e-9", "1e9", "0.5", "2", "-1e300",
                 std::to_string(current * 10), std::to_string(current / 10),
                 std::to_string(current * 1e-6), std::to_string(current * 1e6)});
  }
  if (p.rfind("[Integer", 0) == 0)
    return pick({"0", "1", "2", "3", "8", "100", "-1", "1000000", "4294967295"});
  if (p.rfind("[Bool", 0) == 0)
    return pick({"true", "false"});
  if (p.rfind("[Selection", 0) == 0)
  {
    const auto a = p.find(' '), b = p.rfind(']');
    std::vector<std::string> options;
    std::stringstream list(p.substr(a + 1, b - a - 1));
    for (std::string o; std::getline(list, o, '|');)
      options.push_back(o.substr(0, o.find_last_not_of(' ') + 1));
    return pick(options);
  }
  return pick({"",
               "0",
               "1",
               "x",
               "nan",
               "inf",
               "1/0",
               "0/0",
               "0, 0",
               "0, 0, 0",
               "1e300, 1e300",
               "-1, -1",
               "sin(",
               "\"quoted\"",
               "0; 0",
               "1/(x-x); 0",
               "t > 0.0001 ? 1/0 : 0; 0",
               "rectangle(0, 0, 1e-9, 1e-9)",
               "disc(0, 0, 1e300)",
               "10*0.001",
               "1e9*1",
               "a=1",
               "0, 0.5, 0.25, 0.5",
               e.value + e.value});
}

} // namespace

TEST(Fuzz, RandomEditsOfTheScenesRunOrFailCleanly)
{
  // A fixed seed in CI; LME_MPM_FUZZ_CASES and LME_MPM_FUZZ_SEED for longer runs
  // (scripts/fuzz.sh). Fewer cases in a sanitizer (Debug) build.
  const bool debug           = std::string(LME_MPM_BUILD_TYPE) == "Debug";
  const char *n_env          = std::getenv("LME_MPM_FUZZ_CASES");
  const char *s_env          = std::getenv("LME_MPM_FUZZ_SEED");
  const unsigned int n_cases = n_env ? std::atoi(n_env) : (debug ? 100 : 1000);
  std::mt19937 rng(s_env ? std::atoi(s_env) : 2026);
  // Entries whose edits would take the output elsewhere or lift the step limit.
  const std::vector<std::string> skip = {"Output/Directory", "Time/Maximum steps",
                                         "Output/Verbosity"};
  std::map<std::string, std::vector<Entry>> scenes;
  for (const std::string s : {"vibrating_bar.prm", "two_disk_collision.prm",
                              "vibrating_bar_3d.prm", "tension_bar.prm"})
    for (const auto &e : scene_entries(lme_mpm_test::scene(s)))
      if (std::find(skip.begin(), skip.end(), e.path) == skip.end())
        scenes[s].push_back(e);

  std::map<std::string, unsigned int> outcome;
  const std::string out = lme_mpm_test::scratch("fuzz");
  for (unsigned int k = 0; k < n_cases; ++k)
  {
    auto s = scenes.begin();
    std::advance(s,
                 std::uniform_int_distribution<std::size_t>(0, scenes.size() - 1)(rng));
    const auto &entries = s->second;
    const Entry &e =
        entries[std::uniform_int_distribution<std::size_t>(0, entries.size() - 1)(rng)];
    const std::string edit = e.path + "=" + random_value(e, rng);
    std::filesystem::remove_all(out);
    // In-process (a process per case spent most of its time starting MPI): a crash
    // ends the test, a hang runs into ctest's time limit; the exit codes of the
    // command line are BadInput.CommandLineExitCodes' business.
    const auto start = std::chrono::steady_clock::now();
    std::string msg;
    bool threw = false;
    try
    {
      std::ostringstream quiet;
      dealii::MultithreadInfo::set_thread_limit(1);
      lme_mpm::run_parameter_file(lme_mpm_test::scene(s->first),
                                  {edit, "Output/Directory=" + out, "Output/Verbosity=0",
                                   "Time/Maximum steps=20"},
                                  quiet);
    }
    catch (const std::exception &ex)
    {
      threw = true;
      msg   = "lme-mpm: error: " + lme_mpm::input::concise_message(ex);
    }
    dealii::MultithreadInfo::set_thread_limit();
    const int rc = threw ? 1 : 0;
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (seconds > 3)
      std::cout << seconds << " s: " << s->first << " --set \"" << edit << "\""
                << std::endl;
    SCOPED_TRACE(s->first + " --set \"" + edit + "\": " + (threw ? msg : "no error"));
    nlohmann::json summary;
    const bool has_summary = std::filesystem::exists(out + "/summary.json");
    if (has_summary)
    {
      ASSERT_NO_THROW(
          summary = nlohmann::json::parse(lme_mpm_test::file_text(out + "/summary.json")))
          << "summary.json is not valid JSON";
    }
    if (rc == 0)
    {
      ASSERT_TRUE(has_summary);
      // Every case asks for 20 steps: the run ends at the end time, at its scene's
      // stop rule, or at the step limit, never quietly short of all three.
      const std::string status = summary["status"];
      EXPECT_TRUE(status == "completed" || status == "stopped") << status;
      if (status == "stopped")
      {
        EXPECT_TRUE(summary["stop_reason"] == "Time/Maximum steps" ||
                    summary["stop_reason"] == "scene");
        if (summary["stop_reason"] == "Time/Maximum steps")
        {
          EXPECT_EQ(summary["steps"].get<double>(), 20.0);
        }
      }
      EXPECT_GE(summary["steps"].get<double>(), 1.0);
      ++outcome[status == "stopped"
                    ? "stopped (" + summary["stop_reason"].get<std::string>() + ")"
                    : "completed"];
      continue;
    }
    ASSERT_NE(msg.find("lme-mpm: error: "), std::string::npos);
    if (has_summary)
    {
      EXPECT_EQ(summary["status"], "aborted");
    }
    if (msg.find("Invalid input for '") != std::string::npos ||
        msg.find("no such entry") != std::string::npos)
      ++outcome[has_summary ? "input error during the run" : "input error"];
    else
    {
      // A run-time guard: it names the step, the particle and the cause.
      EXPECT_NE(msg.find("Run stopped at step"), std::string::npos);
      ++outcome["run-time guard"];
      std::cout << "guard: " << s->first << " --set \"" << edit << "\": " << msg
                << std::endl;
    }
  }
  for (const auto &[what, count] : outcome)
    std::cout << count << " " << what << std::endl;
}
