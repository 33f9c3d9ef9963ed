#include <lme_mpm/base/parallel.h>
#include <lme_mpm/simulation/explicit_step.h>

#include <optional>

namespace lme_mpm
{
template <int dim>
ExplicitStep<dim>::ExplicitStep(SimulationParts<dim> &parts, const RunGuard<dim> &guard)
    : parts(parts), guard(guard)
{
  stage.crack_growth        = timer.add("crack growth");
  stage.locate              = timer.add("locate and sort particles");
  stage.to_grid             = timer.add("shape functions, particles to grid");
  stage.rates               = timer.add("rates (predictor)");
  stage.stresses_and_forces = timer.add("strains, stresses, forces");
  stage.stresses            = timer.add("strains and stresses");
  stage.fracture            = timer.add("fracture");
  stage.forces              = timer.add("forces");
  stage.accelerations       = timer.add("accelerations (corrector)");
  stage.to_particles        = timer.add("grid to particles");
  stage.contact             = timer.add("contact (bodies, crack faces)");
  stage.exchange            = timer.add("MPI: particle exchange");
  stage.mass_solve          = timer.add("consistent mass solve");
}

template <int dim>
void ExplicitStep<dim>::set_up(const double dt_, const double mass_tolerance,
                               const double reach, const double spacing)
{
  dt               = dt_;
  min_mass         = mass_tolerance;
  crack_reach      = reach;
  particle_spacing = spacing;
  newmark.gamma    = parts.parameters.newmark_gamma;
}

template <int dim>
StepResult ExplicitStep<dim>::advance(const double t, const unsigned int step)
{
  if (!initialised)
    initialise(t, step);
  grow_cracks();
  locate_and_sort(t, step);
  particles_to_grid();
  predict_rates(t + 0.5 * dt);
  stresses_and_forces(t + dt);
  return update_particles(t, correct_accelerations(t + dt));
}

template <int dim>
double ExplicitStep<dim>::fastest_particle() const
{
  const ParticleStore<dim> &particles = parts.particles;
  double v2                           = 0;
  for (std::size_t p = 0; p < particles.size(); ++p)
    if (!particles.ghost[p])
      v2 = std::max(v2, particles.velocity[p].norm_square());
  return parts.ranks.max(std::sqrt(v2));
}

template <int dim>
void ExplicitStep<dim>::exchange_particles()
{
  if (!parts.ranks.distributed())
    return;
  StageTimer::Scope scope(timer, stage.exchange);
  parts.ranks.exchange(parts.particles);
}

template <int dim>
void ExplicitStep<dim>::impose_rates(std::vector<Tensor<1, dim>> &x, const double t) const
{
  parts.contact.impose_prescribed_rates(x, t);
  parts.constraints.impose_rates(x, parts.transfer.nodes().layout, t);
}

template <int dim>
void ExplicitStep<dim>::impose_accelerations(std::vector<Tensor<1, dim>> &x,
                                             const double t) const
{
  parts.contact.impose_prescribed_accelerations(x, t, derivative_step());
  parts.constraints.impose_accelerations(x, parts.transfer.nodes().layout, t,
                                         derivative_step());
}

template <int dim>
void ExplicitStep<dim>::solve_mass(std::vector<Tensor<1, dim>> &x,
                                   const std::vector<Tensor<1, dim>> &rhs,
                                   const typename MassSolve<dim>::Constrain &constrain,
                                   const char *what, const double t)
{
  if (!parts.mass.active())
    return;
  // The corrections stay in their caller's stage; the solve has its own.
  std::optional<StageTimer::Scope> scope;
  if (parts.mass.consistent())
    scope.emplace(timer, stage.mass_solve);
  parts.mass.solve(parts.transfer, x, rhs, min_mass, constrain, what, t);
}

template <int dim>
void ExplicitStep<dim>::initialise(const double t, const unsigned int step)
{
  // The scheme starts from a^0 = M^-1 f(u^0): with a body force, an initial stress or
  // an accelerating prescribed velocity, a^0 = 0 would lose dt/2 a^0 in the first
  // predictor and corrector and leave a lasting velocity offset (first order in dt).
  GridTransfer<dim> &transfer = parts.transfer;
  NodalFields<dim> &nodes     = transfer.nodes();
  locate_and_sort(t, step);
  particles_to_grid();
  const Tensor<1, dim> body_force = parts.parameters.body_force_at(t);
  transfer.scatter_chunks([&](const std::size_t b, const std::size_t e)
                          { transfer.forces(b, e, body_force); });
  transfer.accelerations(min_mass);
  const auto constrain = [&](std::vector<Tensor<1, dim>> &x)
  { impose_accelerations(x, t); };
  constrain(nodes.acceleration);
  solve_mass(nodes.acceleration, nodes.force, constrain, "initial accelerations", t);
  // Bodies that start in contact (a block resting on a slab) do not accelerate into
  // each other (after the mass corrections, which would undo it).
  transfer.predict_rates(newmark, 0, min_mass);
  parts.contact.impose_prescribed_rates(nodes.rate, t);
  parts.contact.on_initial_accelerations(min_mass);
  if (parts.contact.n_contact_pairs() > 0)
    constrain(nodes.acceleration);
  transfer.interpolate_accelerations();
  initialised = true;
  // The ghosts' a^0 near the halo's outer edge came from incomplete nodes: their
  // owners' values replace them before the first step reads them.
  parts.ranks.exchange(parts.particles);
}

template <int dim>
void ExplicitStep<dim>::grow_cracks()
{
  // A crack that grew with last step's failures separates the field along its new
  // part from this step on.
  CrackSet<dim> &cracks = parts.cracks;
  if (!parts.fracture.active() || cracks.empty())
    return;
  StageTimer::Scope scope(timer, stage.crack_growth);
  bool grown = false;
  if (!parts.ranks.distributed())
    grown = cracks.grow(parts.particles, particle_spacing);
  else if (cracks.grows())
  {
    // Every rank grows its copy of the cracks from the same particles.
    ParticleStore<dim> view;
    parts.ranks.gather_failed(parts.particles,
                              CrackSet<dim>::growth_reach(particle_spacing), view);
    grown = cracks.grow(view, particle_spacing);
  }
  if (grown)
    cracks.assign_fields(parts.grid, crack_reach, parts.transfer.nodes().layout);
}

template <int dim>
void ExplicitStep<dim>::locate_and_sort(const double t, const unsigned int step)
{
  StageTimer::Scope scope(timer, stage.locate);
  guard.stop_if_lost(parts.transfer.locate_and_sort(), step, t);
  // Bodies get their own fields where their supports may meet.
  StageTimer::Scope contact_scope(timer, stage.contact);
  parts.contact.assign_fields(parts.particles, parts.transfer.nodes().layout);
}

template <int dim>
bool ExplicitStep<dim>::full_rows_needed() const
{
  // The parts that read the connectivity's rows besides the transfers: explicit
  // cracks and their face contact, body fields and their contact, rigid surfaces,
  // the mass matrix.
  return !parts.cracks.empty() || parts.contact.active() || parts.rigid.active() ||
         parts.mass.active();
}

template <int dim>
void ExplicitStep<dim>::particles_to_grid()
{
  StageTimer::Scope scope(timer, stage.to_grid);
  // Explicit cracks send the particle-node pairs that cross them to second fields.
  std::uint8_t *touched = parts.cracks.empty()
                              ? nullptr
                              : parts.crack_contact.touched(parts.particles.size());
  parts.transfer.particles_to_grid(
      *parts.shape_function, parts.constraints.all_nodes(),
      [&](const std::size_t b, const std::size_t e)
      {
        parts.cracks.separate(parts.particles, parts.grid, parts.transfer.connectivity(),
                              b, e, touched);
        parts.contact.separate(parts.transfer.connectivity(), b, e);
      },
      full_rows_needed());
  if (parts.mass.consistent())
  {
    // Both solves of the step use this connectivity.
    StageTimer::Scope mass_scope(timer, stage.mass_solve);
    parts.mass.assemble(parts.transfer, parts.particles);
  }
}

template <int dim>
void ExplicitStep<dim>::predict_rates(const double t_half)
{
  StageTimer::Scope scope(timer, stage.rates);
  GridTransfer<dim> &transfer = parts.transfer;
  NodalFields<dim> &nodes     = transfer.nodes();
  transfer.predict_rates(newmark, dt, min_mass);
  parts.contact.impose_prescribed_rates(nodes.rate, t_half);
  {
    StageTimer::Scope contact_scope(timer, stage.contact);
    parts.crack_contact.on_rates(min_mass);
  }
  parts.constraints.impose_rates(nodes.rate, nodes.layout, t_half);
  if (parts.mass.active())
  {
    nodes.for_active(
        [&](const unsigned int I)
        { nodes.rhs[I] = nodes.momentum[I] + (0.5 * dt) * nodes.mass_acceleration[I]; });
    solve_mass(
        nodes.rate, nodes.rhs,
        [&](std::vector<Tensor<1, dim>> &x) { impose_rates(x, t_half); },
        "rates (predictor)", t_half);
  }
  // Contact between bodies last: constraints still win on their nodes.
  {
    StageTimer::Scope contact_scope(timer, stage.contact);
    parts.contact.on_rates(min_mass, dt);
  }
  if (parts.contact.n_contact_pairs() > 0)
    parts.constraints.impose_rates(nodes.rate, nodes.layout, t_half);
}

template <int dim>
void ExplicitStep<dim>::stresses_and_forces(const double t_new)
{
  // The forces of the end of the step.
  GridTransfer<dim> &transfer     = parts.transfer;
  ParticleStore<dim> &particles   = parts.particles;
  const Tensor<1, dim> body_force = parts.parameters.body_force_at(t_new);
  if (!parts.fracture.active())
  {
    // Without it each particle's strain, stress and force follow one another,
    // chunk by chunk while its connectivity is in cache: the same arithmetic in
    // the same order, one pass over the connectivity fewer.
    StageTimer::Scope scope(timer, stage.stresses_and_forces);
    transfer.scatter_chunks(
        [&](const std::size_t b, const std::size_t e)
        {
          transfer.strain_increments(b, e, dt);
          parts.materials.update_stress(particles, b, e);
          transfer.forces(b, e, body_force);
        });
    return;
  }
  // The fracture update couples particles through their neighbourhoods: all
  // stresses (and the snapshot the models read) first, in one pass.
  {
    StageTimer::Scope scope(timer, stage.stresses);
    parts.fracture.prepare(particles);
    parallel::for_range(particles.size(),
                        [&](const std::size_t b, const std::size_t e)
                        {
                          transfer.strain_increments(b, e, dt);
                          parts.materials.update_stress(particles, b, e);
                          parts.fracture.take_snapshot(particles, b, e);
                        });
  }
  {
    StageTimer::Scope scope(timer, stage.fracture);
    parts.fracture.update(particles, &parts.cracks, true);
  }
  StageTimer::Scope scope(timer, stage.forces);
  transfer.scatter_chunks([&](const std::size_t b, const std::size_t e)
                          { transfer.forces(b, e, body_force); });
}

template <int dim>
typename ExplicitStep<dim>::Corrected
ExplicitStep<dim>::correct_accelerations(const double t_new)
{
  Corrected result;
  StageTimer::Scope scope(timer, stage.accelerations);
  GridTransfer<dim> &transfer = parts.transfer;
  NodalFields<dim> &nodes     = transfer.nodes();
  if (parts.rigid.active())
  {
    // The rigid surfaces push on the end-of-step positions (the forces of t_new).
    StageTimer::Scope contact_scope(timer, stage.contact);
    result.rigid_work = parts.rigid.apply(transfer, parts.particles, t_new - dt, dt);
  }
  transfer.accelerations(min_mass);
  parts.contact.impose_prescribed_accelerations(nodes.acceleration, t_new,
                                                derivative_step());
  {
    StageTimer::Scope contact_scope(timer, stage.contact);
    parts.crack_contact.on_accelerations(newmark, dt);
  }
  const auto constrain = [&](std::vector<Tensor<1, dim>> &x)
  { parts.constraints.impose_accelerations(x, nodes.layout, t_new, derivative_step()); };
  constrain(nodes.acceleration);
  solve_mass(
      nodes.acceleration, nodes.force,
      [&](std::vector<Tensor<1, dim>> &x) { impose_accelerations(x, t_new); },
      "accelerations (corrector)", t_new);
  {
    StageTimer::Scope contact_scope(timer, stage.contact);
    result.contact_work = parts.contact.on_accelerations(newmark, dt);
  }
  if (parts.contact.n_contact_pairs() > 0)
    constrain(nodes.acceleration);
  if (!parts.mass.active() || parts.constraints.empty())
    return result;
  // The reaction is what the constraint adds to the force: M a - f on its nodes.
  transfer.apply_consistent_mass(nodes.acceleration, nodes.rhs);
  result.mass_times_acceleration = &nodes.rhs;
  return result;
}

template <int dim>
StepResult ExplicitStep<dim>::update_particles(const double t, const Corrected &corrected)
{
  StageTimer::Scope scope(timer, stage.to_particles);
  const NodalFields<dim> &nodes = parts.transfer.nodes();
  const double work             = parts.constraints.update_reactions(
                  nodes.layout, nodes.mass, nodes.acceleration, nodes.force,
                  corrected.mass_times_acceleration, nodes.rate, dt);
  StepResult result;
  result.first_bad = parts.particles.size();
  if (parts.parameters.xpic_order > 0)
    parts.transfer.extend_start_velocity(parts.parameters.xpic_order, min_mass,
                                         [&](std::vector<Tensor<1, dim>> &x)
                                         { impose_rates(x, t); });
  // Under a ramp, the body force of the middle of the step does its work.
  const double body_work = parts.transfer.grid_to_particles(
      newmark, dt, parts.parameters.body_force_at(t + 0.5 * dt),
      0.5 * parts.grid.min_spacing(), result.first_bad, result.max_speed);
  // The constraints' work is summed over the ranks already.
  // The rigid surfaces' work is summed over the ranks already.
  result.external_work =
      work + corrected.rigid_work + parts.ranks.sum(body_work + corrected.contact_work);
  parts.rigid.finish_step();
  return result;
}

template class ExplicitStep<2>;
template class ExplicitStep<3>;
} // namespace lme_mpm
