#ifndef LME_MPM_SOLVER_SIMULATION_H
#define LME_MPM_SOLVER_SIMULATION_H

// Forwarding header, kept for one release: the driver moved to simulation/, and
// run_parameter_file() is declared in simulation/run.h.
#include <lme_mpm/simulation/run.h>
#include <lme_mpm/simulation/simulation.h>

#endif
