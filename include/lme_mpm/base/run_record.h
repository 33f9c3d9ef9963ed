#ifndef LME_MPM_BASE_RUN_RECORD_H
#define LME_MPM_BASE_RUN_RECORD_H

#include <string>
#include <vector>

namespace lme_mpm
{
/// The release of the library (the project's version) and the git revision of its
/// sources when the build was configured ("unknown" outside a git checkout).
const char *version();
const char *git_revision();
/// "lme-mpm <version> (git <revision>, <build type>)".
std::string version_line();

/**
 * What a run was started with, kept in its output: summary.json's "run" object and the
 * complete parameter set as parameters.prm (the handler after the file, the --set
 * values and the scene's entries), so that any output directory says how to redo it.
 */
struct RunRecord
{
  std::string command_line; ///< as the program was called (empty from the library)
  std::string parameter_file;
  std::vector<std::string> overrides; ///< the --set values, in order
  std::vector<std::string> libraries; ///< Additional shared libraries loaded
  std::string resumed_from;           ///< --resume directory, if any
  std::string parameters;             ///< the whole handler in PRM form
};

/**
 * The first entry whose value differs between two parameter sets in PRM form (as
 * RunRecord::parameters holds them), as "Subsection/Entry: 'old' -> 'new'"; empty if
 * none does. Entries that do not change results are skipped: the Output and Checkpoint
 * subsections and Time/Maximum steps.
 */
std::string first_changed_entry(const std::string &before, const std::string &after);
} // namespace lme_mpm

#endif
