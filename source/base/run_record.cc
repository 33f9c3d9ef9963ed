#include <lme_mpm/base/run_record.h>

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
} // namespace lme_mpm
