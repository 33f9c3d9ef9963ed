#ifndef LME_MPM_SOLVER_RUN_FAILED_H
#define LME_MPM_SOLVER_RUN_FAILED_H

#include <deal.II/base/exceptions.h>

#include <string>

namespace lme_mpm
{
/**
 * A particle of some rank went wrong: every rank of a distributed run stops with the
 * diagnostic (@p arg1) of the rank that holds it.
 */
DeclException1(ExcRunStopped, std::string, << arg1);

/**
 * The run ended before its end time with its output written (@p arg1 says why). On
 * several ranks every rank throws it together, unlike an error on one rank.
 */
DeclException1(ExcRunFailed, std::string, << arg1);
} // namespace lme_mpm

#endif
