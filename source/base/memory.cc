#include <lme_mpm/base/input.h>
#include <lme_mpm/base/memory.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>

#include <sys/resource.h>

namespace lme_mpm
{
namespace memory
{
double available_bytes()
{
  // LME_MPM_MEMORY_LIMIT (bytes) caps it, for a job's share of a node (and tests).
  double limit = std::numeric_limits<double>::max();
  if (const char *env = std::getenv("LME_MPM_MEMORY_LIMIT"))
    limit = std::atof(env);
  std::ifstream meminfo("/proc/meminfo");
  std::string key, unit;
  double value;
  while (meminfo >> key >> value >> unit)
    if (key == "MemAvailable:")
      return std::min(limit, value * 1024.0);
  return limit;
}

void require(const double bytes, const std::string &entry, const std::string &what)
{
  const double available = available_bytes();
  if (std::isfinite(bytes) && bytes <= available)
    return;
  std::ostringstream msg;
  msg.precision(3);
  msg << what << " needs about " << bytes / 1e9 << " GB; this machine has "
      << available / 1e9 << " GB available";
  AssertThrow(false, ExcBadInput(entry, msg.str()));
}

double peak_resident_bytes()
{
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0)
    return 0;
  return 1024.0 * usage.ru_maxrss; // kilobytes on Linux
}
} // namespace memory
} // namespace lme_mpm
