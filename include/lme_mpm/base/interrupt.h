#ifndef LME_MPM_BASE_INTERRUPT_H
#define LME_MPM_BASE_INTERRUPT_H

namespace lme_mpm
{
/**
 * Ctrl-C and `kill`: the program installs handlers for SIGINT and SIGTERM that only
 * record the signal; the time loop looks at it after each step and ends the run as
 * `interrupted`, with its output and (where checkpoints are on) a checkpoint of that
 * step. A second signal ends the process at once.
 */
namespace interrupt
{
/// Installs the handlers (the stock program does; library users may).
void install();
/// The signal received since install() (0: none).
int received();
/// "SIGINT", "SIGTERM" or "signal N".
const char *name(int signal);
} // namespace interrupt
} // namespace lme_mpm

#endif
