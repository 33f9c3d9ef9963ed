#include <lme_mpm/base/input.h>
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

std::string first_changed_entry(const std::string &before, const std::string &after)
{
  const auto a = input::entry_values(before), b = input::entry_values(after);
  const auto ignored = [](const std::string &key)
  {
    // Entries that change what is written or how far the run goes, not its steps:
    // a run resumed with a later End time is extended.
    return key.rfind("Output/", 0) == 0 || key.rfind("Checkpoint/", 0) == 0 ||
           key == "Time/Maximum steps" || key == "Time/End time";
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
