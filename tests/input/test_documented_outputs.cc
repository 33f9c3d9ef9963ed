// Every key a run writes into summary.json and every column of its CSV files is
// documented in doc/outputs.md: each scene of prm/ runs a few steps and its output
// names are matched against the names the page's tables give (a name with a
// placeholder, force_<set>_x, stands for any name in its place).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "test_helpers.h"

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

namespace
{
/// The names in the first column of doc/outputs.md's tables, as patterns.
std::vector<std::pair<std::string, std::regex>> documented_names()
{
  std::ifstream in(std::string(LME_MPM_SOURCE_DIR) + "/doc/outputs.md");
  std::vector<std::pair<std::string, std::regex>> names;
  for (std::string line; std::getline(in, line);)
  {
    if (line.rfind("| `", 0) != 0)
      continue;
    const auto end = line.find('`', 3);
    if (end == std::string::npos)
      continue;
    const std::string name = line.substr(3, end - 3);
    // A row made of placeholders alone (<model>_<statistic>) would match any name: it
    // documents a family in words, not names the test can check.
    if (name.find('<') != std::string::npos &&
        std::regex_replace(name, std::regex("<[^>]*>"), "").size() < 4)
      continue;
    std::string pattern;
    for (std::size_t i = 0; i < name.size(); ++i)
    {
      if (name[i] == '<')
      {
        const auto close = name.find('>', i);
        if (close != std::string::npos)
        {
          pattern += "[A-Za-z0-9_.+-]+";
          i = close;
          continue;
        }
      }
      if (std::string(".^$|()[]{}*+?\\").find(name[i]) != std::string::npos)
        pattern += '\\';
      pattern += name[i];
    }
    names.emplace_back(name, std::regex(pattern));
  }
  return names;
}

bool documented(const std::string &name,
                const std::vector<std::pair<std::string, std::regex>> &names)
{
  for (const auto &n : names)
    if (std::regex_match(name, n.second))
      return true;
  return false;
}

/// The keys of a JSON object, nested objects' keys joined with '.'.
void collect_keys(const nlohmann::json &j, const std::string &prefix,
                  std::set<std::string> &keys)
{
  for (auto it = j.begin(); it != j.end(); ++it)
  {
    const std::string key = prefix + it.key();
    if (it->is_object())
      collect_keys(*it, key + ".", keys);
    else
      keys.insert(key);
  }
}

/// The header of a CSV file (its first line, split on ',').
std::vector<std::string> csv_header(const std::string &file)
{
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  return lme_mpm::input::split(line, ',');
}
} // namespace

TEST(Documentation, EveryOutputKeyAndColumnIsDocumented)
{
  const auto names = documented_names();
  ASSERT_GT(names.size(), 50u) << "doc/outputs.md lists too few names";
  std::set<std::string> undocumented;
  unsigned int scenes = 0;
  for (const auto &entry :
       std::filesystem::directory_iterator(std::string(LME_MPM_SOURCE_DIR) + "/prm"))
  {
    if (entry.path().extension() != ".prm")
      continue;
    const std::string scene = entry.path().stem().string();
    const std::string out   = lme_mpm_test::scratch("documented_" + scene);
    SCOPED_TRACE(scene);
    lme_mpm_test::run_scene(
        entry.path().filename().string(), "documented_" + scene,
        {"Time/Maximum steps=3", "Output/Write particle files=false"});
    ++scenes;
    std::set<std::string> keys;
    collect_keys(nlohmann::json::parse(lme_mpm_test::file_text(out + "/summary.json")),
                 "", keys);
    for (const auto &key : keys)
      if (!documented(key, names))
        undocumented.insert("summary.json: " + key + " (" + scene + ")");
    for (const std::string csv :
         {"history.csv", "damage.csv", "cracks.csv", "failed_particles.csv"})
      if (std::filesystem::exists(out + "/" + csv))
        for (const auto &column : csv_header(out + "/" + csv))
          if (!documented(column, names))
            undocumented.insert(csv + ": " + column + " (" + scene + ")");
  }
  EXPECT_GE(scenes, 12u);
  std::string list;
  for (const auto &u : undocumented)
    list += "\n  " + u;
  EXPECT_TRUE(undocumented.empty()) << "not in doc/outputs.md:" << list;
}
