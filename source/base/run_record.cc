#include <lme_mpm/base/run_record.h>

#include <map>
#include <sstream>

// Set for this file only by CMakeLists.txt, so a new revision rebuilds one file.
#ifndef LME_MPM_VERSION
#define LME_MPM_VERSION "unknown"
#endif
#ifndef LME_MPM_GIT_REVISION
#define LME_MPM_GIT_REVISION "unknown"
#endif
#ifndef LME_MPM_BUILD_TYPE_NAME
#define LME_MPM_BUILD_TYPE_NAME "unknown"
#endif

namespace lme_mpm
{
const char *version()
{
  return LME_MPM_VERSION;
}

const char *git_revision()
{
  return LME_MPM_GIT_REVISION;
}

std::string version_line()
{
  return std::string("lme-mpm ") + version() + " (git " + git_revision() + ", " +
         LME_MPM_BUILD_TYPE_NAME + " build)";
}

namespace
{
/// "Subsection/.../Entry" -> value of every 'set' line of a PRM text.
std::map<std::string, std::string> entry_values(const std::string &text)
{
  std::map<std::string, std::string> values;
  std::vector<std::string> path;
  std::istringstream in(text);
  std::string line;
  const auto trim = [](const std::string &s)
  {
    const auto b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
    return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
  };
  while (std::getline(in, line))
  {
    line = trim(line);
    if (line.rfind("subsection ", 0) == 0)
      path.push_back(trim(line.substr(11)));
    else if (line == "end" && !path.empty())
      path.pop_back();
    else if (line.rfind("set ", 0) == 0)
    {
      const auto eq = line.find('=');
      if (eq == std::string::npos)
        continue;
      std::string key;
      for (const auto &p : path)
        key += p + "/";
      values[key + trim(line.substr(4, eq - 4))] = trim(line.substr(eq + 1));
    }
  }
  return values;
}
} // namespace

std::string first_changed_entry(const std::string &before, const std::string &after)
{
  const auto a = entry_values(before), b = entry_values(after);
  const auto ignored = [](const std::string &key)
  {
    return key.rfind("Output/", 0) == 0 || key.rfind("Checkpoint/", 0) == 0 ||
           key == "Time/Maximum steps";
  };
  for (const auto &[key, value] : a)
  {
    if (ignored(key))
      continue;
    const auto other      = b.find(key);
    const std::string now = other == b.end() ? "(not declared)" : other->second;
    if (now != value)
      return key + ": '" + value + "' -> '" + now + "'";
  }
  for (const auto &[key, value] : b)
    if (!ignored(key) && a.count(key) == 0)
      return key + ": (not declared) -> '" + value + "'";
  return "";
}
} // namespace lme_mpm
