#ifndef LME_MPM_SOLVER_RUN_H
#define LME_MPM_SOLVER_RUN_H

// Forwarding header, kept for one release: see simulation/run.h.
#include <lme_mpm/simulation/run.h>

#endif
