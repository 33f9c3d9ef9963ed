#ifndef LME_MPM_SIMULATION_HALO_REACH_H
#define LME_MPM_SIMULATION_HALO_REACH_H

#include <lme_mpm/contact/body_contact.h>
#include <lme_mpm/distributed/halo.h>
#include <lme_mpm/fracture/fracture_coupling.h>
#include <lme_mpm/grid/background_grid.h>
#include <lme_mpm/shape_functions/shape_function.h>

namespace lme_mpm
{
/**
 * What one explicit step of a particle reads, for the halo of a distributed run
 * (Decomposition::partition, HaloCells). Its nodes, the particles sharing those nodes,
 * and theirs again (strains from nodal velocities, then forces from the stresses): four
 * support radii, two particle-node-particle passes. Each consistent-mass correction
 * pass adds a support there and back in the predictor and in the corrector, the
 * reactions' consistent mass M_C a one support more, and body contact the supports
 * its exchange passes through (BodyContact::reach). Fracture reads the particles
 * within the epsilon-neighbourhood and the crack band directly.
 *
 * Every length is the local one: a node's support radius
 * (ShapeFunction::node_support_radius) and a cell's fracture reach from its own
 * spacing, so where a graded grid is fine the halo is as many fine cells wide as it
 * would be coarse cells where the grid is coarse.
 */
template <int dim>
HaloReach
halo_reach(const BackgroundGrid<dim> &grid, const ShapeFunction<dim> &shape_function,
           const FractureCoupling<dim> &fracture, const BodyContact<dim> &contact,
           unsigned int mass_corrections, unsigned int xpic_order = 0);
} // namespace lme_mpm

#endif
