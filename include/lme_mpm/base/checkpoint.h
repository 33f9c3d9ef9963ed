#ifndef LME_MPM_BASE_CHECKPOINT_H
#define LME_MPM_BASE_CHECKPOINT_H

#include <lme_mpm/base/archive.h>

#include <functional>
#include <string>

namespace lme_mpm
{
namespace checkpoint
{
/**
 * Writes @p file through @p serialize, after the format's magic and version.
 * Atomic (files::write_atomically): the data go to file.tmp, which replaces the file
 * only when complete; the file it replaces is kept as file.prev. A checkpoint that
 * cannot be completed (a full disk) throws ExcCannotWrite and leaves both as they were.
 */
void write(const std::string &file, const std::function<void(Archive &)> &serialize);

/**
 * Reads @p file through @p serialize after checking the magic and the version.
 * Throws ExcBadInput("--resume", ...) for a missing, foreign, other-version or
 * truncated file.
 */
void read(const std::string &file, const std::function<void(Archive &)> &serialize);
} // namespace checkpoint
} // namespace lme_mpm

#endif
