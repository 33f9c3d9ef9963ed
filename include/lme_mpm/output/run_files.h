#ifndef LME_MPM_OUTPUT_RUN_FILES_H
#define LME_MPM_OUTPUT_RUN_FILES_H

#include <string>

namespace lme_mpm
{
/**
 * Removes from @p directory the files an earlier run of lme-mpm wrote there: the
 * history, summary, parameter record, damage and crack files, the particle and grid
 * series (PVD records, VTU files and the distributed runs' pieces and PVTU files) and
 * the checkpoints. A new run into the same directory then cannot leave another run's
 * files beside its own (ParaView groups `particles_*.vtu` into one series). Other
 * files are left alone. Returns how many files were removed.
 */
unsigned int remove_earlier_run(const std::string &directory);

/// True if @p name is the name of a file lme-mpm writes into an output directory.
bool is_run_file(const std::string &name);
} // namespace lme_mpm

#endif
