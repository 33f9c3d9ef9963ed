#ifndef LME_MPM_SIMULATION_PARTS_H
#define LME_MPM_SIMULATION_PARTS_H

#include <lme_mpm/boundary/node_constraints.h>
#include <lme_mpm/contact/body_contact.h>
#include <lme_mpm/contact/crack_face_contact.h>
#include <lme_mpm/contact/loading_control.h>
#include <lme_mpm/contact/rigid_surfaces.h>
#include <lme_mpm/distributed/decomposition.h>
#include <lme_mpm/fracture/crack_set.h>
#include <lme_mpm/fracture/fracture_coupling.h>
#include <lme_mpm/geometry/bodies.h>
#include <lme_mpm/grid/background_grid.h>
#include <lme_mpm/materials/material_set.h>
#include <lme_mpm/particles/particle_store.h>
#include <lme_mpm/scenes/scene.h>
#include <lme_mpm/shape_functions/shape_function.h>
#include <lme_mpm/solver/grid_transfer.h>
#include <lme_mpm/solver/mass_solve.h>
#include <lme_mpm/solver/run_parameters.h>

#include <memory>

namespace lme_mpm
{
/**
 * The parts of one run, owned together: the grid, the particles and everything that
 * acts on them. Simulation builds and wires them; the explicit step (ExplicitStep)
 * advances them, the output (RunOutput) reads them, and the checkpoint saves them,
 * each handed this one object instead of a reference per part (as deal.II's step-69
 * hands its TimeStep the OfflineData).
 */
template <int dim>
struct SimulationParts
{
  SimulationParts()
      : transfer(grid, particles), crack_contact(cracks, transfer, particles),
        contact(grid, transfer, particles, bodies), mass(parameters)
  {
  }
  SimulationParts(const SimulationParts &) = delete;

  RunParameters<dim> parameters;
  std::unique_ptr<Scene<dim>> scene;
  Decomposition<dim> ranks;
  BackgroundGrid<dim> grid;
  /// This rank's particles: its own and, in a distributed run, ghosts.
  ParticleStore<dim> particles;
  MaterialSet<dim> materials;
  FractureCoupling<dim> fracture;
  CrackSet<dim> cracks;
  std::unique_ptr<ShapeFunction<dim>> shape_function;
  NodeConstraints<dim> constraints;
  Bodies<dim> bodies;
  GridTransfer<dim> transfer;
  CrackFaceContact<dim> crack_contact;
  BodyContact<dim> contact;
  /// Prescribed bodies with Surface = exact.
  RigidSurfaces<dim> rigid;
  OpeningGauges<dim> gauges;
  LoadingControl<dim> control;
  MassSolve<dim> mass;

  /// True if bodies receive contact forces (multi-field contact or rigid surfaces).
  bool contact_forces() const { return contact.active() || rigid.active(); }
};
} // namespace lme_mpm

#endif
