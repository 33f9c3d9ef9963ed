#include <deal.II/base/multithread_info.h>

#include <lme_mpm/base/format.h>
#include <lme_mpm/base/input.h>
#include <lme_mpm/base/parallel.h>
#include <lme_mpm/base/plugin_libraries.h>
#include <lme_mpm/geometry/particle_generator.h>
#include <lme_mpm/solver/checkpoint.h>
#include <lme_mpm/solver/halo_reach.h>
#include <lme_mpm/solver/run_failed.h>
#include <lme_mpm/solver/simulation.h>

#include <filesystem>
#include <iomanip>
#include <numeric>
#include <sstream>

namespace lme_mpm
{
// ------------------------------------------------------------------ setup

template <int dim>
void Simulation<dim>::declare_parameters(ParameterHandler &prm,
                                         const ParameterCounts &counts)
{
  ParameterCounts::declare_parameters(prm);
  PluginLibraries::declare_parameters(prm);
  RunParameters<dim>::declare_parameters(prm);
  declare_scene_parameters<dim>(prm);
  BackgroundGrid<dim>::declare_parameters(prm);
  CrackSet<dim>::declare_parameters(prm);
  MaterialSet<dim>::declare_parameters(prm, counts.materials);
  FractureCoupling<dim>::declare_parameters(prm, counts.materials);
  ParticleGenerator<dim>::declare_parameters(prm, counts.bodies);
  NodeConstraints<dim>::declare_parameters(prm, counts.constraints);
  BodyContact<dim>::declare_parameters(prm, counts.bodies);
  Probes<dim>::declare_parameters(prm, counts.probes);
  ExactSolution<dim>::declare_parameters(prm);
}

template <int dim>
Simulation<dim>::Simulation(ParameterHandler &prm, const ParameterCounts &counts,
                            std::ostream &console)
    : console_stream(console), pcout(console, false), transfer(background, store),
      crack_contact(cracks, transfer, store), contact(background, transfer, store)
{
  stage.crack_growth        = stages.add("crack growth");
  stage.locate              = stages.add("locate and sort particles");
  stage.to_grid             = stages.add("shape functions, particles to grid");
  stage.rates               = stages.add("rates (predictor)");
  stage.stresses_and_forces = stages.add("strains, stresses, forces");
  stage.stresses            = stages.add("strains and stresses");
  stage.fracture            = stages.add("fracture");
  stage.forces              = stages.add("forces");
  stage.accelerations       = stages.add("accelerations (corrector)");
  stage.to_particles        = stages.add("grid to particles");
  stage.contact             = stages.add("contact (bodies, crack faces)");
  stage.exchange            = stages.add("MPI: particle exchange");
  parameters.parse_parameters(prm);
  {
    SceneContext<dim> context;
    context.thickness     = parameters.thickness;
    context.n_bodies      = counts.bodies;
    context.n_constraints = counts.constraints;
    prm.enter_subsection("Contact");
    context.contact = prm.get("Type") != "none";
    prm.leave_subsection();
    scene = create_scene<dim>(prm, context);
    scene->set_entries(prm);
    scene->adjust(parameters);
  }
  output_directory = parameters.directory;
  pcout.set_condition(parameters.verbosity > 0 && ranks.rank() == 0);
  newmark.gamma = parameters.newmark_gamma;

  background.parse_parameters(prm);
  cracks.parse_parameters(prm, counts.bodies);
  materials.parse_parameters(prm, counts.materials, parameters.plane_stress);
  fracture.parse_parameters(prm, materials, background, parameters.thickness);

  const TimeStepping ts =
      stable_time_step(parameters, background.min_spacing(), materials.max_wave_speed());
  dt      = ts.dt;
  n_steps = ts.n_steps;

  setup_particles(prm, counts);
  double min_mass = std::numeric_limits<double>::max();
  for (const double m : store.mass)
    min_mass = std::min(min_mass, m);
  mass_tolerance = 1e-12 * min_mass;

  ShapeFunctionContext<dim> sf_context;
  sf_context.grid      = &background;
  sf_context.thickness = parameters.thickness;
  prm.enter_subsection("Shape functions");
  shape_function = ShapeFunctionRegistry<dim>::instance().create(
      parameters.shape_function, prm, sf_context);
  prm.leave_subsection();
  if (fracture.active())
  {
    // A band width tied to the grid spans the band these functions spread a crack
    // over, which depends on where the body's particles sit in their cells.
    std::vector<double> width, reach;
    for (const auto &band :
         crack_bands(*shape_function, background, body_placements, parameters.thickness))
      width.push_back(band.width_cells), reach.push_back(band.reach_cells);
    fracture.set_crack_band(width, reach);
  }
  transfer.nodes().layout.reinit(background.n_nodes());
  if (!cracks.empty())
  {
    crack_reach = shape_function->support_radius(background);
    cracks.assign_fields(background, crack_reach, transfer.nodes().layout);
  }

  constraints.parse_parameters(prm, counts.constraints, background);
  {
    std::vector<std::string> set_names;
    for (unsigned int c = 0; c < constraints.size(); ++c)
      set_names.push_back(constraints[c].name());
    contact.parse_parameters(prm, counts.bodies, parameters.thickness,
                             shape_function->support_radius(background), set_names);
    if (contact.any_prescribed())
    {
      transfer.set_prescribed_bodies(contact.prescribed_bodies());
      energy.set_excluded_bodies(contact.prescribed_bodies());
      contact.set_prescribed_velocities(store, 0);
    }
    // A crack's second fields belong to the cracked body; its faces' contact pairs
    // them with that body's field at the node, which contact may have moved off the
    // node's own index.
    if (contact.active() && !cracks.empty())
      crack_contact.set_near_field([this](const unsigned int I)
                                   { return contact.field_of_body(I, cracks.body()); });
    scene->check(scene_state());
  }
  peak_force.parse(parameters.peak_force_set, constraints);
  probes.parse_parameters(prm, counts.probes);
  exact.parse_parameters(prm);

  if (parameters.output_interval <= 0)
    parameters.output_interval = parameters.end_time / 20;
  setup_output(output_directory);
  distribute();
}

template <int dim>
void Simulation<dim>::distribute()
{
  n_particles  = store.size();
  initial_mass = std::accumulate(store.mass.begin(), store.mass.end(), 0.0);
  if (!ranks.distributed())
    return;
  // The halo holds what one step of an owned particle reads (solver/halo_reach.h).
  const auto reach = halo_reach(background, *shape_function, fracture, contact,
                                parameters.mass_corrections);
  ranks.partition(background, reach);
  ranks.distribute(store);
  particles_split = true;
  transfer.set_reach_agreement(
      [this](unsigned int &below, unsigned int &above)
      {
        below = static_cast<unsigned int>(ranks.max(below));
        above = static_cast<unsigned int>(ranks.max(above));
      });
  fracture.set_max_over_ranks([this](const double h) { return ranks.max(h); });
  constraints.set_distribution(&ranks.owned_nodes(),
                               [this](std::vector<double> &v) { ranks.sum(v); });
  contact.set_distribution(&ranks.owned_nodes(),
                           [this](std::vector<double> &v) { ranks.sum(v); });
  pcout << "lme-mpm: " << ranks.n_ranks() << " MPI ranks; " << reach.support_passes
        << " support passes in the halo; rank 0 owns " << ranks.n_owned_cells()
        << " cells and keeps " << ranks.n_halo_cells() << " halo cells, "
        << Decomposition<dim>::n_owned(store) << " particles and "
        << store.size() - Decomposition<dim>::n_owned(store) << " ghosts" << std::endl;
}

template <int dim>
const ParticleStore<dim> &Simulation<dim>::observed() const
{
  if (!ranks.distributed())
    return store;
  ranks.gather(store, gathered);
  return gathered;
}

template <int dim>
void Simulation<dim>::stop_if_any(const std::size_t p,
                                  const std::function<void(std::size_t)> &stop) const
{
  if (!ranks.distributed())
  {
    if (p < store.size())
      stop(p);
    return;
  }
  constexpr unsigned long long none = ~0ull;
  const unsigned long long mine     = p < store.size() ? store.id[p] : none;
  const unsigned long long lowest   = ranks.min(mine);
  if (lowest == none)
    return;
  // The rank holding the particle words the diagnostic; every rank stops with it.
  std::string message;
  if (mine == lowest)
    try
    {
      stop(p);
    }
    catch (const ExcRunAborted &e)
    {
      message = input::concise_message(e);
    }
  const auto holder = static_cast<unsigned int>(
      ranks.min(mine == lowest ? ranks.rank() : ranks.n_ranks()));
  AssertThrow(false, ExcRunStopped(ranks.broadcast(message, holder)));
}

template <int dim>
void Simulation<dim>::setup_output(const std::string &directory)
{
  output_directory = directory;
  particle_output  = std::make_unique<ParticleOutput<dim>>(directory);
  grid_output      = std::make_unique<GridOutput<dim>>(directory);
}

template <int dim>
void Simulation<dim>::setup_particles(ParameterHandler &prm,
                                      const ParameterCounts &counts)
{
  std::vector<double> densities;
  for (unsigned int m = 0; m < materials.size(); ++m)
    densities.push_back(materials[m].density());
  const auto bodies = ParticleGenerator<dim>::fill(
      prm, counts.bodies, background, densities, parameters.thickness, store);
  const double h_min = background.min_spacing();
  body_placements.clear();
  for (const auto &body : bodies)
  {
    body_placements.emplace_back(body.offsets, body.weights);
    particle_spacing = std::min(particle_spacing, h_min / body.particles_per_cell);
    // Only the cells the body starts in bound its neighbourhoods.
    fracture.check_neighbourhood(body.material, body.particles_per_cell, body.section,
                                 &body.cells);
    for (const unsigned int m : body.zone_materials)
      fracture.check_neighbourhood(m, body.particles_per_cell, body.section, &body.cells);
  }
  // The time step comes from the wave speed; the motion the input starts must not
  // carry a particle half a cell in one step either (the run guard would stop it at
  // step 1 and blame the CFL number).
  std::size_t fastest = 0;
  for (std::size_t p = 0; p < store.size(); ++p)
    if (store.velocity[p].norm() > store.velocity[fastest].norm())
      fastest = p;
  if (store.size() > 0)
  {
    const double v = store.velocity[fastest].norm();
    std::ostringstream msg;
    msg << "the initial speed " << v << " m/s at "
        << point_to_string(store.position[fastest]) << " carries a particle " << v * dt
        << " m in one step of dt = " << dt << " s, more than half the smallest cell ("
        << 0.5 * h_min << " m): lower the speed or Time/CFL";
    AssertThrow(v * dt <= 0.5 * h_min,
                ExcBadInput(bodies[store.body_id[fastest]].section + "/Initial velocity",
                            msg.str()));
  }
  {
    const double g = parameters.body_force.norm();
    std::ostringstream msg;
    msg << "|b| = " << g << " m/s^2 moves a particle " << 0.5 * g * dt * dt
        << " m in one step of dt = " << dt << " s, more than half the smallest cell ("
        << 0.5 * h_min << " m)";
    AssertThrow(0.5 * g * dt * dt <= 0.5 * h_min,
                ExcBadInput("Problem/Body force", msg.str()));
  }
}

// ------------------------------------------------------------------ one step

template <int dim>
void Simulation<dim>::step()
{
  const double t_half = t + 0.5 * dt, t_new = t + dt;
  if (!accelerations_initialised)
    initialise_accelerations();
  // A crack that grew with last step's failures separates the field along its new
  // part from this step on.
  if (fracture.active() && !cracks.empty())
  {
    StageTimer::Scope scope(stages, stage.crack_growth);
    bool grown = false;
    if (!ranks.distributed())
      grown = cracks.grow(store, particle_spacing);
    else if (cracks.grows())
    {
      // Every rank grows its copy of the cracks from the same particles.
      ParticleStore<dim> view;
      ranks.gather_failed(store, CrackSet<dim>::growth_reach(particle_spacing), view);
      grown = cracks.grow(view, particle_spacing);
    }
    if (grown)
      cracks.assign_fields(background, crack_reach, transfer.nodes().layout);
  }
  locate_and_sort();
  particles_to_grid();
  predict_displacement_rates(t_half);
  update_stresses_and_forces();
  const std::size_t bad = update_particles(correct_accelerations());
  t                     = t_new;
  ++step_count;
  stop_if_any(bad, [this](const std::size_t p) { abort_unstable(p); });
  if (ranks.distributed())
  {
    StageTimer::Scope scope(stages, stage.exchange);
    ranks.exchange(store);
  }
}

template <int dim>
void Simulation<dim>::initialise_accelerations()
{
  // The scheme starts from a^0 = M^-1 f(u^0): with a body force, an initial stress or
  // an accelerating prescribed velocity, a^0 = 0 would lose dt/2 a^0 in the first
  // predictor and corrector and leave a lasting velocity offset (first order in dt).
  NodalFields<dim> &nodes = transfer.nodes();
  locate_and_sort();
  particles_to_grid();
  const Tensor<1, dim> body_force = parameters.body_force_at(t);
  transfer.scatter_chunks([&](const std::size_t b, const std::size_t e)
                          { transfer.forces(b, e, body_force); });
  transfer.accelerations(mass_tolerance);
  const auto constrain = [&](std::vector<Tensor<1, dim>> &x)
  {
    contact.impose_prescribed_accelerations(x, t, derivative_step());
    constraints.impose_accelerations(x, nodes.layout, t, derivative_step());
  };
  constrain(nodes.acceleration);
  transfer.correct_towards_consistent_mass(nodes.acceleration, nodes.force,
                                           parameters.mass_corrections, mass_tolerance,
                                           constrain);
  // Bodies that start in contact (a block resting on a slab) do not accelerate into
  // each other (after the mass corrections, which would undo it).
  transfer.predict_rates(newmark, 0, mass_tolerance);
  contact.impose_prescribed_rates(nodes.rate, t);
  contact.on_initial_accelerations(mass_tolerance);
  if (contact.n_contact_pairs() > 0)
    constrain(nodes.acceleration);
  transfer.interpolate_accelerations();
  accelerations_initialised = true;
  // The ghosts' a^0 near the halo's outer edge came from incomplete nodes: their
  // owners' values replace them before the first step reads them.
  ranks.exchange(store);
}

template <int dim>
SceneState<dim> Simulation<dim>::scene_state() const
{
  SceneState<dim> state;
  // Output reads every particle: on rank 0, as gathered for this output.
  // (before the split, every rank holds them all).
  state.particles   = particles_split ? &gathered : &store;
  state.body_names  = &contact.body_names();
  state.run         = &parameters;
  state.constraints = &constraints;
  if (contact.active())
  {
    state.contact_forces      = &contact.mean_forces();
    state.peak_contact_forces = &contact.peak_forces();
  }
  state.time = t;
  return state;
}

template <int dim>
void Simulation<dim>::abort_run(const std::size_t p, const std::string &why) const
{
  AssertThrow(false, ExcRunAborted(step_count, t, store.id[p],
                                   point_to_string(store.position[p]), why));
}

template <int dim>
void Simulation<dim>::locate_and_sort()
{
  StageTimer::Scope scope(stages, stage.locate);
  const std::size_t lost = transfer.locate_and_sort();
  stop_if_any(lost,
              [this](const std::size_t p)
              {
                abort_run(p, "the particle left the background grid (enlarge the grid, "
                             "or the run is unstable: lower the CFL number)");
              });
  // Bodies get their own fields where their supports may meet.
  {
    StageTimer::Scope contact_scope(stages, stage.contact);
    contact.assign_fields(store, transfer.nodes().layout);
  }
}

template <int dim>
void Simulation<dim>::particles_to_grid()
{
  StageTimer::Scope scope(stages, stage.to_grid);
  // Explicit cracks send the particle-node pairs that cross them to second fields.
  std::uint8_t *touched = cracks.empty() ? nullptr : crack_contact.touched(store.size());
  transfer.particles_to_grid(*shape_function, constraints.all_nodes(),
                             [&](const std::size_t b, const std::size_t e)
                             {
                               cracks.separate(store, background, transfer.connectivity(),
                                               b, e, touched);
                               contact.separate(transfer.connectivity(), b, e);
                             });
}

template <int dim>
void Simulation<dim>::predict_displacement_rates(const double t_half)
{
  StageTimer::Scope scope(stages, stage.rates);
  NodalFields<dim> &nodes = transfer.nodes();
  transfer.predict_rates(newmark, dt, mass_tolerance);
  const auto constrain = [&](std::vector<Tensor<1, dim>> &x)
  {
    contact.impose_prescribed_rates(x, t_half);
    constraints.impose_rates(x, nodes.layout, t_half);
  };
  contact.impose_prescribed_rates(nodes.rate, t_half);
  {
    StageTimer::Scope contact_scope(stages, stage.contact);
    crack_contact.on_rates(mass_tolerance);
  }
  constraints.impose_rates(nodes.rate, nodes.layout, t_half);
  if (parameters.mass_corrections > 0)
  {
    nodes.for_active(
        [&](const unsigned int I)
        { nodes.rhs[I] = nodes.momentum[I] + (0.5 * dt) * nodes.mass_acceleration[I]; });
    transfer.correct_towards_consistent_mass(
        nodes.rate, nodes.rhs, parameters.mass_corrections, mass_tolerance, constrain);
  }
  // Contact between bodies last: constraints still win on their nodes.
  {
    StageTimer::Scope contact_scope(stages, stage.contact);
    contact.on_rates(mass_tolerance, dt);
  }
  if (contact.n_contact_pairs() > 0)
    constraints.impose_rates(nodes.rate, nodes.layout, t_half);
}

template <int dim>
void Simulation<dim>::update_stresses_and_forces()
{
  // The forces of the end of the step.
  const Tensor<1, dim> body_force = parameters.body_force_at(t + dt);
  const auto stresses             = [&](const std::size_t b, const std::size_t e)
  { materials.update_stress(store, b, e); };
  if (fracture.active())
  {
    // The fracture update couples particles through their neighbourhoods: all
    // stresses (and the snapshot the models read) first, in one pass.
    {
      StageTimer::Scope scope(stages, stage.stresses);
      fracture.prepare(store);
      parallel::for_range(store.size(),
                          [&](const std::size_t b, const std::size_t e)
                          {
                            transfer.strain_increments(b, e, dt);
                            stresses(b, e);
                            fracture.take_snapshot(store, b, e);
                          });
    }
    {
      StageTimer::Scope scope(stages, stage.fracture);
      fracture.update(store, &cracks, true);
    }
    StageTimer::Scope scope(stages, stage.forces);
    transfer.scatter_chunks([&](const std::size_t b, const std::size_t e)
                            { transfer.forces(b, e, body_force); });
  }
  else
  {
    // Without it each particle's strain, stress and force follow one another,
    // chunk by chunk while its connectivity is in cache: the same arithmetic in
    // the same order, one pass over the connectivity fewer.
    StageTimer::Scope scope(stages, stage.stresses_and_forces);
    transfer.scatter_chunks(
        [&](const std::size_t b, const std::size_t e)
        {
          transfer.strain_increments(b, e, dt);
          stresses(b, e);
          transfer.forces(b, e, body_force);
        });
  }
}

template <int dim>
const std::vector<Tensor<1, dim>> *Simulation<dim>::correct_accelerations()
{
  StageTimer::Scope scope(stages, stage.accelerations);
  NodalFields<dim> &nodes = transfer.nodes();
  transfer.accelerations(mass_tolerance);
  contact.impose_prescribed_accelerations(nodes.acceleration, t + dt, derivative_step());
  {
    StageTimer::Scope contact_scope(stages, stage.contact);
    crack_contact.on_accelerations(newmark, dt);
  }
  const auto impose = [&](std::vector<Tensor<1, dim>> &x)
  { constraints.impose_accelerations(x, nodes.layout, t + dt, derivative_step()); };
  const auto constrain = [&](std::vector<Tensor<1, dim>> &x)
  {
    contact.impose_prescribed_accelerations(x, t + dt, derivative_step());
    impose(x);
  };
  impose(nodes.acceleration);
  if (parameters.mass_corrections > 0)
    transfer.correct_towards_consistent_mass(nodes.acceleration, nodes.force,
                                             parameters.mass_corrections, mass_tolerance,
                                             constrain);
  {
    StageTimer::Scope contact_scope(stages, stage.contact);
    contact_work = contact.on_accelerations(newmark, dt);
  }
  if (contact.n_contact_pairs() > 0)
    impose(nodes.acceleration);
  if (parameters.mass_corrections == 0 || constraints.empty())
    return nullptr;
  // The reaction is what the constraint adds to the force: M a - f on its nodes.
  transfer.apply_consistent_mass(nodes.acceleration, nodes.rhs);
  return &nodes.rhs;
}

template <int dim>
std::size_t Simulation<dim>::update_particles(
    const std::vector<Tensor<1, dim>> *mass_times_acceleration)
{
  StageTimer::Scope scope(stages, stage.to_particles);
  const NodalFields<dim> &nodes = transfer.nodes();
  const double work =
      constraints.update_reactions(nodes.layout, nodes.mass, nodes.acceleration,
                                   nodes.force, mass_times_acceleration, nodes.rate, dt);
  peak_force.update(constraints);
  std::size_t bad = store.size();
  // Under a ramp, the body force of the middle of the step does its work.
  const double body_work =
      transfer.grid_to_particles(newmark, dt, parameters.body_force_at(t + 0.5 * dt),
                                 0.5 * background.min_spacing(), bad);
  // The constraints' work is summed over the ranks already.
  energy.add_external_work(work + ranks.sum(body_work + contact_work));
  return bad;
}

template <int dim>
void Simulation<dim>::abort_unstable(const std::size_t bad) const
{
  std::string why;
  if (!std::isfinite(store.velocity[bad].norm_square()))
    why = "non-finite velocity (the run is unstable: lower the CFL number)";
  else if (!(store.density[bad] > 0))
    why = "non-positive density (the material is inverted: the run is unstable, lower "
          "the CFL number, or the deformation is too large for a small-strain model)";
  else
    why = "the particle moved more than half a cell in one step (the run is "
          "unstable or the time step too large: lower the CFL number)";
  abort_run(bad, why);
}

// ------------------------------------------------------------------ checkpoints

template <int dim>
void Simulation<dim>::serialize(Archive &ar)
{
  // Everything a resumed run needs to continue bit for bit: the particles, the
  // driver's accumulators and the output series. Nodal fields are rebuilt every step.
  // A distributed run writes one file per rank, each with that rank's particles
  // (owned and ghosts) and its copy of the rest: it resumes on as many ranks, which
  // p4est splits alike.
  std::uint32_t file_dim = dim, file_steps = n_steps, file_ranks = ranks.n_ranks();
  std::uint64_t n = n_particles;
  double file_dt  = dt;
  ar(file_dim, file_ranks, n, file_dt, file_steps);
  if (ar.loading())
  {
    std::ostringstream mismatch;
    mismatch << "the checkpoint holds a " << file_dim << "D run of " << n
             << " particles with dt = " << file_dt << " s; this parameter file gives "
             << dim << "D, " << n_particles << " particles, dt = " << dt
             << " s: resume with the parameter file (and --set "
             << "values) of the run that wrote it";
    AssertThrow(file_dim == dim && n == n_particles && file_dt == dt,
                ExcBadInput("--resume", mismatch.str()));
    AssertThrow(file_ranks == ranks.n_ranks(),
                ExcBadInput("--resume", "the checkpoint was written on " +
                                            std::to_string(file_ranks) +
                                            " MPI ranks; resume on as many (mpirun -np " +
                                            std::to_string(file_ranks) + ")"));
  }
  ar(t, step_count);
  transfer.serialize(ar);
  energy.serialize(ar);
  ar(next_output_time);
  peak_force.serialize(ar);
  exact.serialize(ar);
  // Only rank 0 writes history.csv.
  std::uint64_t history_size = ar.loading() || !writes_output() ? 0 : history.size();
  ar(history_size);
  if (ar.loading())
    resumed_history_size = history_size;
  constraints.serialize(ar);
  contact.serialize(ar);
  scene->serialize(ar);
  auto particle_series = particle_output->series();
  auto grid_series     = grid_output->series();
  ar(particle_series, grid_series);
  store.for_each_field([&](auto &field) { ar(field); });
  auto lines = cracks.polylines();
  ar(lines);
  if (!ar.loading())
    return;
  AssertThrow(ar.good() && lines.size() == cracks.polylines().size(),
              ExcBadInput("--resume", "the checkpoint holds " +
                                          std::to_string(lines.size()) +
                                          " cracks, the parameter file " +
                                          std::to_string(cracks.polylines().size())));
  particle_output->restore(particle_series);
  grid_output->restore(grid_series);
  cracks.restore(std::move(lines));
  transfer.nodes().layout.reinit(background.n_nodes());
  cracks.assign_fields(background, crack_reach, transfer.nodes().layout);
}

template <int dim>
void Simulation<dim>::write_checkpoint()
{
  checkpoint::write(checkpoint_file(output_directory),
                    [&](Archive &ar) { serialize(ar); });
}

template <int dim>
std::string Simulation<dim>::checkpoint_file(const std::string &directory) const
{
  return directory + (ranks.distributed()
                          ? "/checkpoint." + std::to_string(ranks.rank()) + ".bin"
                          : "/checkpoint.bin");
}

template <int dim>
void Simulation<dim>::resume_from(const std::string &directory)
{
  // Output goes on in the checkpoint's directory.
  setup_output(directory);
  // Files of a run on another number of ranks: name the number to use. Every rank
  // decides alike from the same files (one rank stopping alone would leave the
  // others waiting).
  const std::string file = checkpoint_file(directory);
  unsigned int per_rank  = 0;
  while (std::filesystem::exists(directory + "/checkpoint." + std::to_string(per_rank) +
                                 ".bin"))
    ++per_rank;
  const bool one_rank           = std::filesystem::exists(directory + "/checkpoint.bin");
  const unsigned int written_on = ranks.distributed() ? (per_rank > 0 ? per_rank
                                                         : one_rank   ? 1
                                                                      : 0)
                                                      : (one_rank ? 1 : per_rank);
  AssertThrow(written_on == 0 || written_on == ranks.n_ranks(),
              ExcBadInput("--resume", "the checkpoint in '" + directory +
                                          "' was written on " +
                                          std::to_string(written_on) +
                                          " MPI rank(s): resume on as many (mpirun -np " +
                                          std::to_string(written_on) + ")"));
  if (ranks.distributed())
    AssertThrow(ranks.min(std::filesystem::exists(file) ? 1ull : 0ull) == 1,
                ExcBadInput("--resume", "no checkpoint '" + file + "' on every rank"));
  checkpoint::read(file, [&](Archive &ar) { serialize(ar); });
  store.mark_reordered();
  AssertThrow(step_count <= n_steps,
              ExcBadInput("--resume", "the checkpoint is past this run's end time"));
  resumed                   = true;
  accelerations_initialised = true;
}

template <int dim>
std::uint64_t Simulation<dim>::state_checksum()
{
  // FNV-1a of each owned particle's fields, summed over the particles (and ranks):
  // the same state gives the same sum whatever the order and split of the particles.
  auto fnv = [](std::uint64_t hash, const void *data, const std::size_t size)
  {
    const auto *c = static_cast<const unsigned char *>(data);
    for (std::size_t i = 0; i < size; ++i)
      hash = (hash ^ c[i]) * 1099511628211ull;
    return hash;
  };
  constexpr std::uint64_t basis = 1469598103934665603ull;
  unsigned long long total      = 0;
  for (std::size_t p = 0; p < store.size(); ++p)
    if (!store.ghost[p])
    {
      std::uint64_t hash = basis;
      store.for_each_field([&](auto &field)
                           { hash = fnv(hash, &field[p], sizeof(field[p])); });
      total += hash;
    }
  return fnv(basis, &t, sizeof(t)) + ranks.sum(total);
}

// ------------------------------------------------------------------ output

template <int dim>
std::map<std::string, double> Simulation<dim>::energies() const
{
  const ParticleStore<dim> &all = observed();
  return energy.measure(all, materials).as_map();
}

template <int dim>
void Simulation<dim>::write_output_row()
{
  // A distributed run reads every particle on rank 0, which writes the files.
  const ParticleStore<dim> &all = observed();
  std::vector<double> nodal_mass, nodal_rate;
  if (parameters.write_grid && ranks.distributed())
  {
    // Each node from the rank that owns it (elsewhere its sums miss particles).
    const unsigned int n = background.n_nodes();
    nodal_mass.assign(n * (1 + dim), 0.0);
    for (unsigned int I = 0; I < n && I < transfer.nodes().mass.size(); ++I)
      if (ranks.owns_node(I))
      {
        nodal_mass[I] = transfer.nodes().mass[I];
        for (unsigned int d = 0; d < dim; ++d)
          nodal_mass[n + I * dim + d] = transfer.nodes().rate[I][d];
      }
    ranks.sum(nodal_mass);
  }
  // Each rank writes its own particles.
  if (parameters.write_particles && ranks.distributed())
    particle_output->write_piece(store, t, ranks.rank(), ranks.n_ranks());
  if (!writes_output())
    return;
  const Energies e = energy.measure(all, materials);
  energy.record(e, step_count == 0);
  std::ostringstream row;
  row << std::setprecision(10) << step_count << "," << t << ",";
  EnergyBalance<dim>::write_row(row, e);
  constraints.write_row(row);
  contact.write_row(row, all);
  probes.write_row(row, all);
  scene->write_history_row(row, scene_state());
  exact.write_row(row, all, t);
  history.write_row(row.str());
  results["final_total_energy"]   = e.total();
  results["final_kinetic_energy"] = e.kinetic;
  results["final_strain_energy"]  = e.strain;

  if (parameters.write_particles && !ranks.distributed())
    particle_output->write(store, t);
  if (parameters.write_grid && ranks.distributed())
  {
    const unsigned int n = background.n_nodes();
    std::vector<double> mass(nodal_mass.begin(), nodal_mass.begin() + n);
    std::vector<Tensor<1, dim>> rate(n);
    for (unsigned int I = 0; I < n; ++I)
      for (unsigned int d = 0; d < dim; ++d)
        rate[I][d] = nodal_mass[n + I * dim + d];
    grid_output->write(background, mass, rate, t);
  }
  else if (parameters.write_grid)
    grid_output->write(background, transfer.nodes().mass, transfer.nodes().rate, t);
}

template <int dim>
void Simulation<dim>::prepare_output()
{
  exact.compute_norms(observed(), parameters.end_time, parameters.output_interval);

  // Only now, with every input checked, does the run write anything (rank 0 makes
  // the directory the others write their pieces to).
  if (writes_output())
    std::filesystem::create_directories(output_directory);
  ranks.barrier();
  if (!writes_output())
    return;
  if (resumed)
    history.resume(output_directory, resumed_history_size);
  else
  {
    std::ostringstream header;
    header << "step,time,";
    EnergyBalance<dim>::write_header(header);
    constraints.write_header(header);
    contact.write_header(header);
    probes.write_header(header);
    scene->write_history_header(header);
    exact.write_header(header);
    history.create(output_directory, header.str());
  }
  pcout << "lme-mpm: " << dim << "D, " << n_particles << " particles, "
        << background.n_nodes() << " nodes, shape functions '" << shape_function->name()
        << "', dt = " << dt << " s, " << n_steps << " steps, " << transfer.threads()
        << " thread(s)" << std::endl;
}

template <int dim>
void Simulation<dim>::report_progress(const std::chrono::steady_clock::time_point start)
{
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  pcout << "  step " << std::setw(8) << step_count << "  t = " << std::setw(12)
        << std::setprecision(5) << t << "  " << std::setw(3) << 100 * step_count / n_steps
        << "%  " << std::setprecision(3) << n_particles * step_count / elapsed
        << " particle-steps/s  ETA " << std::setprecision(3)
        << elapsed * (n_steps - step_count) / step_count << " s" << std::endl;
}

// ------------------------------------------------------------------ driver

template <int dim>
void Simulation<dim>::advance_to_end(TimerOutput &timer,
                                     const std::chrono::steady_clock::time_point start)
{
  const double output_interval = parameters.output_interval;
  if (!resumed)
  {
    TimerOutput::Scope scope(timer, "output");
    write_output_row();
    next_output_time = output_interval;
  }
  auto last_checkpoint            = std::chrono::steady_clock::now();
  const unsigned int report_every = std::max(1u, n_steps / 10);
  while (step_count < n_steps)
  {
    {
      TimerOutput::Scope scope(timer, "time step");
      step();
    }
    if (t >= next_output_time - 0.5 * dt || step_count == n_steps)
    {
      TimerOutput::Scope scope(timer, "output");
      write_output_row();
      // The first output time past this step (an interval below the rounding of t
      // would never move it by addition).
      next_output_time =
          output_interval * (std::floor((t + 0.5 * dt) / output_interval) + 1);
      const std::string reason =
          ranks.broadcast(writes_output() ? scene->finished(scene_state()) : "");
      if (!reason.empty())
      {
        results["stopped_early"] = 1;
        stop_reason              = reason;
        pcout << "Stopped at t = " << t << ": " << reason << std::endl;
        break;
      }
    }
    const bool by_steps = parameters.checkpoint_every_steps > 0 &&
                          step_count % parameters.checkpoint_every_steps == 0;
    // Every rank writes its part at the same step: the slowest rank's clock decides.
    const bool by_time = parameters.checkpoint_every_seconds > 0 &&
                         ranks.max(std::chrono::duration<double>(
                                       std::chrono::steady_clock::now() - last_checkpoint)
                                       .count()) >= parameters.checkpoint_every_seconds;
    if ((by_steps || by_time) && step_count < n_steps)
    {
      TimerOutput::Scope scope(timer, "checkpoint");
      write_checkpoint();
      last_checkpoint = std::chrono::steady_clock::now();
    }
    if (step_count % report_every == 0 || step_count == n_steps)
      report_progress(start);
    if (parameters.max_steps > 0 && step_count >= parameters.max_steps &&
        step_count < n_steps)
      AssertThrow(false, ExcStepLimit(step_count, t));
  }
}

template <int dim>
RunSummary Simulation<dim>::summarise(const double wall)
{
  // Every rank takes part in the gathering; rank 0 summarises.
  const ParticleStore<dim> &all = observed();
  RunSummary summary;
  if (!writes_output())
    return summary;
  results["wall_seconds"]              = wall;
  results["steps"]                     = step_count;
  results["particles"]                 = n_particles;
  results["ranks"]                     = ranks.n_ranks();
  results["nodes"]                     = background.n_nodes();
  results["threads"]                   = transfer.threads();
  results["time_step"]                 = dt;
  results["particle_steps_per_second"] = n_particles * double(step_count) / wall;
  results["max_energy_drift"]          = energy.max_drift();
  stages.add_results(results);
  peak_force.add_results(results);
  contact.add_results(results);
  scene->add_results(scene_state(), results);
  exact.add_results(results);
  for (const auto &s : shape_function->statistics())
    results["shape_function_" + s.first] = s.second;
  // What the ranks hold now, against what the run started with (migration must
  // neither lose nor copy a particle).
  results["final_particles"] = all.size();
  results["final_mass"]      = std::accumulate(all.mass.begin(), all.mass.end(), 0.0);
  results["initial_mass"]    = initial_mass;
  fracture.add_statistics(all, results);
  if (fracture.active())
  {
    results["dissipated_energy"] =
        energy.measure(all, materials).as_map()["dissipated_energy"];
    write_failed_particles(output_directory + "/failed_particles.csv", all);
    write_damage_field(output_directory + "/damage.csv", all);
  }
  if (!cracks.empty())
  {
    write_polylines(output_directory + "/cracks.csv", cracks.polylines());
    results["crack_second_fields"] = cracks.n_crack_nodes();
  }
  summary.values = results;
  return summary;
}

template <int dim>
void Simulation<dim>::report_balance(const double wall) const
{
  if (!ranks.distributed())
    return;
  // What each rank holds at the end, and how long its exchanges took (waiting for
  // the slowest rank included): tells an uneven split from a costly halo.
  const std::size_t owned = Decomposition<dim>::n_owned(store);
  const auto owned_all    = ranks.all_gather(static_cast<double>(owned));
  const auto ghosts_all   = ranks.all_gather(static_cast<double>(store.size() - owned));
  const auto exchange_all =
      ranks.all_gather(stages.seconds().at("MPI: particle exchange"));
  for (unsigned int r = 0; r < ranks.n_ranks(); ++r)
    pcout << "rank " << r << ": " << owned_all[r] << " particles, " << ghosts_all[r]
          << " ghosts; exchange " << exchange_all[r] << " s of " << wall << " s"
          << std::endl;
}

template <int dim>
std::map<std::string, double> Simulation<dim>::run()
{
  TimerOutput timer(pcout, TimerOutput::never, TimerOutput::wall_times);
  const auto start = std::chrono::steady_clock::now();
  prepare_output();

  std::string status = "completed", message;
  try
  {
    advance_to_end(timer, start);
  }
  catch (const std::exception &e)
  {
    // Any failure inside the loop (an unstable step, a shape-function solve that does
    // not converge) ends the run with what it produced kept on disk.
    status                  = "aborted";
    const bool on_all_ranks = dynamic_cast<const ExcRunAborted *>(&e) != nullptr ||
                              dynamic_cast<const ExcRunStopped *>(&e) != nullptr ||
                              dynamic_cast<const ExcStepLimit *>(&e) != nullptr;
    // An error on one rank only (the others wait in a collective call): the
    // program stops every rank (main.cc); writing output here would hang.
    if (ranks.distributed() && !on_all_ranks)
      throw;
    if (!on_all_ranks)
    {
      std::ostringstream where;
      where << "Run stopped at step " << step_count + 1 << ", time " << t << ": "
            << input::concise_message(e);
      message = where.str();
    }
    else
      message = input::concise_message(e);
    // Keep what the run produced: one last row and particle file at the failure.
    try
    {
      write_output_row();
    }
    catch (...)
    {
    }
  }

  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  RunSummary summary           = summarise(wall);
  summary.status               = status;
  summary.message              = message.empty() ? stop_reason : message;
  const std::uint64_t checksum = state_checksum();
  if (writes_output())
    summary.write(output_directory + "/summary.json", shape_function->name(), checksum,
                  dim);
  // Past this point the output is on disk (on every rank); the caller reports the
  // failure.
  ranks.barrier();
  // Every rank ends alike; main() tells this from an error on one rank only.
  AssertThrow(status == "completed", ExcRunFailed(message));
  timer.print_summary();
  if (pcout.is_active())
    stages.print(pcout.get_stream(), wall);
  report_balance(wall);
  pcout << "Finished: " << step_count << " steps in " << wall << " s ("
        << results["particle_steps_per_second"] << " particle-steps/s); max energy drift "
        << energy.max_drift() << std::endl;
  return results;
}

template class Simulation<2>;
template class Simulation<3>;
} // namespace lme_mpm
