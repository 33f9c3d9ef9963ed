#ifndef LME_MPM_BASE_MEMORY_H
#define LME_MPM_BASE_MEMORY_H

#include <string>

namespace lme_mpm
{
namespace memory
{
/// Memory the system can still give this process (bytes): MemAvailable of
/// /proc/meminfo (a very large number where that is unknown), capped by the
/// environment variable LME_MPM_MEMORY_LIMIT (bytes) if set.
double available_bytes();

/**
 * Throws ExcBadInput naming @p entry if @p bytes (what @p what needs) exceed the
 * available memory, before anything is allocated: a run that would exhaust the
 * machine stops with the amount it needs instead of swapping or being killed.
 */
void require(double bytes, const std::string &entry, const std::string &what);

/// The largest resident set this process has had so far (bytes; getrusage's
/// ru_maxrss): what a run's memory per particle is measured by.
double peak_resident_bytes();
} // namespace memory
} // namespace lme_mpm

#endif
