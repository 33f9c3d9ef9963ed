#include <deal.II/base/timer.h>

#include <lme_mpm/base/file_writing.h>
#include <lme_mpm/base/format.h>
#include <lme_mpm/base/input.h>
#include <lme_mpm/base/interrupt.h>
#include <lme_mpm/base/plugin_libraries.h>
#include <lme_mpm/geometry/particle_generator.h>
#include <lme_mpm/shape_functions/shape_function.h>
#include <lme_mpm/simulation/halo_reach.h>
#include <lme_mpm/simulation/simulation.h>

#include <cstdio>
#include <sstream>

namespace lme_mpm
{
template <int dim>
void Simulation<dim>::declare_parameters(ParameterHandler &prm,
                                         const ParameterCounts &counts)
{
  ParameterCounts::declare_parameters(prm);
  PluginLibraries::declare_parameters(prm);
  RunParameters<dim>::declare_parameters(prm);
  declare_shape_function_parameters<dim>(prm);
  declare_scene_parameters<dim>(prm);
  BackgroundGrid<dim>::declare_parameters(prm);
  CrackSet<dim>::declare_parameters(prm);
  MaterialSet<dim>::declare_parameters(prm, counts.materials);
  FractureCoupling<dim>::declare_parameters(prm, counts.materials);
  ParticleGenerator<dim>::declare_parameters(prm, counts.bodies);
  Bodies<dim>::declare_parameters(prm, counts.bodies);
  NodeConstraints<dim>::declare_parameters(prm, counts.constraints);
  BodyContact<dim>::declare_parameters(prm);
  RigidSurfaces<dim>::declare_parameters(prm);
  LoadingControl<dim>::declare_parameters(prm);
  RunOutput<dim>::declare_parameters(prm, counts.probes);
}

template <int dim>
Simulation<dim>::Simulation(ParameterHandler &prm, const ParameterCounts &counts,
                            std::ostream &console)
    : guard(parts.particles, parts.grid, parts.ranks), stepper(parts, guard),
      output(parts, stepper.stages(), console)
{
  parts.parameters.parse_parameters(prm);
  setup_scene(prm, counts);
  parts.grid.parse_parameters(prm);
  parts.cracks.parse_parameters(prm, counts.bodies);
  parts.materials.parse_parameters(prm, counts.materials, parts.parameters.plane_stress,
                                   parts.parameters.units == "SI");
  parts.fracture.parse_parameters(prm, parts.materials, parts.grid,
                                  parts.parameters.thickness);
  const TimeStepping ts = stable_time_step(parts.parameters, parts.grid.min_spacing(),
                                           parts.materials.max_wave_speed(),
                                           parts.materials.wave_speed_inputs());
  clock.set_up(ts, parts.parameters.end_time, parts.parameters.particle_travel,
               parts.grid.min_spacing());
  dt = ts.dt;
  setup_shape_functions(prm);
  setup_particles(prm, counts);
  couple_shape_functions();
  setup_bodies_and_contact(prm, counts);
  if (parts.parameters.output_interval <= 0)
    parts.parameters.output_interval = parts.parameters.end_time / 20;
  if (parts.parameters.force_window <= 0)
    parts.parameters.force_window =
        10 * parts.grid.min_spacing() / parts.materials.max_wave_speed();
  output.parse_parameters(prm, counts.probes);
  double min_mass = std::numeric_limits<double>::max();
  for (const double m : parts.particles.mass)
    min_mass = std::min(min_mass, m);
  stepper.set_up(dt, 1e-12 * min_mass, crack_reach, particle_spacing);
  parts.rigid.set_reference_step(clock.wave_step());
  distribute();
  parts.rigid.seat(parts.particles, parts.parameters.end_time, parts.grid.min_spacing());
  parts.gauges.check(parts.particles, &parts.ranks);
  parts.control.set_up(parts.particles, parts.materials.max_wave_speed(), &parts.ranks);
  max_speed = stepper.fastest_particle();
}

template <int dim>
void Simulation<dim>::setup_scene(ParameterHandler &prm, const ParameterCounts &counts)
{
  // Every entry as declared: a scene writes an entry only where the file left it
  // at this default.
  ParameterHandler declarations;
  declare_parameters(declarations, counts);
  SceneContext<dim> context;
  context.thickness     = parts.parameters.thickness;
  context.n_bodies      = counts.bodies;
  context.n_constraints = counts.constraints;
  context.contact       = prm.get(std::vector<std::string>{"Contact"}, "Type") != "none";
  context.declarations  = &declarations;
  parts.scene           = create_scene<dim>(prm, context);
  EntryWriter writer(prm, declarations, counts.bodies, counts.constraints);
  parts.scene->write_entries(writer);
  parts.scene->adjust(parts.parameters);
}

template <int dim>
void Simulation<dim>::setup_particles(ParameterHandler &prm,
                                      const ParameterCounts &counts)
{
  std::vector<double> densities;
  for (unsigned int m = 0; m < parts.materials.size(); ++m)
    densities.push_back(parts.materials[m].density());
  const auto bodies =
      ParticleGenerator<dim>::fill(prm, counts.bodies, parts.grid, densities,
                                   parts.parameters.thickness, parts.particles);
  const double h_min = parts.grid.min_spacing();
  face_depths.clear();
  std::vector<std::string> sections;
  for (const auto &body : bodies)
  {
    // A body's outermost particles sit this far inside a face of their cells.
    face_depths.push_back(body.offsets.front() * h_min);
    sections.push_back(body.section);
    particle_spacing = std::min(particle_spacing, h_min / body.particles_per_cell);
    parts.fracture.add_body(body);
  }
  check_initial_motion(sections);
}

template <int dim>
void Simulation<dim>::check_initial_motion(const std::vector<std::string> &sections) const
{
  // The time step comes from the wave speed (and the travel limit, if on); the
  // motion the input starts must not carry a particle half a cell in one step either
  // (the run guard would stop it at step 1 and blame the CFL number).
  const ParticleStore<dim> &store = parts.particles;
  const double h_min              = parts.grid.min_spacing();
  std::size_t fastest             = 0;
  for (std::size_t p = 0; p < store.size(); ++p)
    if (store.velocity[p].norm() > store.velocity[fastest].norm())
      fastest = p;
  if (store.size() > 0)
  {
    const double v  = store.velocity[fastest].norm();
    const double dt = clock.allowed(v);
    std::ostringstream msg;
    msg << "the initial speed " << v << " m/s at "
        << point_to_string(store.position[fastest]) << " carries a particle " << v * dt
        << " m in one step of dt = " << dt << " s, more than half the smallest cell ("
        << 0.5 * h_min
        << " m): lower the speed or Time/CFL, or set Time/Particle travel per step";
    AssertThrow(
        v * dt <= 0.5 * h_min,
        ExcBadInput(sections[store.body_id[fastest]] + "/Initial velocity", msg.str()));
  }
  const double g = parts.parameters.body_force.norm();
  std::ostringstream msg;
  msg << "|b| = " << g << " m/s^2 moves a particle " << 0.5 * g * dt * dt
      << " m in one step of dt = " << dt << " s, more than half the smallest cell ("
      << 0.5 * h_min << " m)";
  AssertThrow(0.5 * g * dt * dt <= 0.5 * h_min,
              ExcBadInput("Problem/Body force", msg.str()));
}

template <int dim>
void Simulation<dim>::setup_shape_functions(ParameterHandler &prm)
{
  ShapeFunctionContext<dim> context;
  context.grid         = &parts.grid;
  context.thickness    = parts.parameters.thickness;
  parts.shape_function = create_shape_function(prm, context);
  // The particles keep only the state the run's parts use (set before they are made,
  // so the dropped fields never count in the run's memory).
  parts.particles.keep_state(
      {parts.shape_function->keeps_particle_state(), parts.fracture.active()});
}

template <int dim>
void Simulation<dim>::couple_shape_functions()
{
  parts.fracture.set_crack_band(*parts.shape_function);
  parts.transfer.nodes().layout.reinit(parts.grid.n_nodes());
  if (!parts.cracks.empty())
  {
    crack_reach = parts.shape_function->support_radius(parts.grid);
    parts.cracks.assign_fields(parts.grid, crack_reach, parts.transfer.nodes().layout);
  }
}

template <int dim>
void Simulation<dim>::setup_bodies_and_contact(ParameterHandler &prm,
                                               const ParameterCounts &counts)
{
  parts.constraints.parse_parameters(prm, counts.constraints, parts.grid);
  std::vector<std::string> set_names;
  for (unsigned int c = 0; c < parts.constraints.size(); ++c)
    set_names.push_back(parts.constraints[c].name());
  parts.bodies.parse_parameters(prm, counts.bodies, set_names);
  parts.contact.parse_parameters(prm, parts.parameters.thickness,
                                 parts.shape_function->support_radius(parts.grid));
  parts.rigid.parse_parameters(prm, parts.bodies, face_depths, parts.grid.min_spacing());
  parts.gauges.parse_parameters(prm, parts.grid.min_spacing());
  parts.gauges.set_excluded_bodies(parts.bodies.prescribed_flags());
  parts.control.parse_parameters(prm, parts.bodies, parts.gauges);
  if (parts.bodies.any_prescribed())
  {
    parts.transfer.set_prescribed_bodies(parts.bodies.prescribed_flags());
    parts.bodies.set_prescribed_velocities(parts.particles, 0);
  }
  // A crack's second fields belong to the cracked body; its faces' contact pairs
  // them with that body's field at the node, which contact may have moved off the
  // node's own index.
  if (parts.contact.active() && !parts.cracks.empty())
    parts.crack_contact.set_body_fields(parts.contact.body_fields());
  parts.scene->check(output.scene_state(t, parts.particles));
}

template <int dim>
void Simulation<dim>::distribute()
{
  n_particles = parts.particles.size();
  output.record_totals();
  // The parts that sum or agree over the ranks (no-ops on one rank).
  parts.transfer.set_ranks(parts.ranks);
  parts.fracture.set_ranks(parts.ranks);
  parts.constraints.set_ranks(parts.ranks);
  parts.contact.set_ranks(parts.ranks);
  parts.rigid.set_ranks(parts.ranks);
  parts.mass.set_ranks(parts.ranks, parts.ranks.communicator());
  if (!parts.ranks.distributed())
    return;
  // The halo holds what one step of an owned particle reads (halo_reach.h).
  const HaloReach reach =
      halo_reach(parts.grid, *parts.shape_function, parts.fracture, parts.contact,
                 parts.parameters.mass_corrections, parts.parameters.xpic_order);
  parts.ranks.partition(parts.grid, reach);
  parts.ranks.distribute(parts.particles);
  output.console() << "lme-mpm: " << parts.ranks.n_ranks() << " MPI ranks; "
                   << reach.support_passes << " support passes in the halo; rank 0 owns "
                   << parts.ranks.n_owned_cells() << " cells and keeps "
                   << parts.ranks.n_halo_cells() << " halo cells, "
                   << Decomposition<dim>::n_owned(parts.particles) << " particles and "
                   << parts.particles.size() -
                          Decomposition<dim>::n_owned(parts.particles)
                   << " ghosts" << std::endl;
}

template <int dim>
void Simulation<dim>::step()
{
  dt = clock.next(t, step_count, max_speed);
  stepper.set_time_step(dt);
  const StepResult result = stepper.advance(t, step_count);
  // The last step lands on the end time to the bit.
  t = clock.at_end() ? clock.end_time() : t + dt;
  ++step_count;
  // One collective call per step for the conductor's maxima: the fastest particle
  // (the next step's length), and the guard's interrupt signal and particle flag.
  step_maxima[0] = result.max_speed;
  step_maxima[1] = interrupt::received();
  step_maxima[2] = result.first_bad < parts.particles.size() ? 1 : 0;
  parts.ranks.max(step_maxima);
  max_speed        = step_maxima[0];
  interrupt_signal = static_cast<int>(step_maxima[1]);
  // The servo reads its gauge after the step and sets the devices' speed for the next.
  parts.control.update(parts.particles, &parts.ranks, t, dt);
  output.after_step(result.external_work, dt, t, max_speed);
  guard.stop_if_unstable(result.first_bad, step_maxima[2] > 0, step_count, t);
  stepper.exchange_particles();
}

template <int dim>
void Simulation<dim>::advance_to_end(TimerOutput &timer,
                                     const std::chrono::steady_clock::time_point start)
{
  if (!resumed)
  {
    TimerOutput::Scope scope(timer, "output");
    output.write_first_row(t);
  }
  auto last_checkpoint            = std::chrono::steady_clock::now();
  const unsigned int report_every = std::max(1u, clock.planned_steps() / 10);
  while (true)
  {
    // Before the last step, which alone is shortened to land on the end time, a run
    // with checkpoints keeps one: extended from it to a later end time, the run takes
    // the steps of one run to that time.
    if (checkpoints_on() && clock.last_step(t, step_count, max_speed))
    {
      TimerOutput::Scope scope(timer, "checkpoint");
      write_checkpoint();
    }
    {
      TimerOutput::Scope scope(timer, "time step");
      step();
    }
    const bool last = clock.finished(t, step_count) || output.stopping();
    if (output.due(t, dt))
    {
      TimerOutput::Scope scope(timer, "output");
      output.write_due_row(step_count, t, dt);
      guard.stop_if_energy_runs_away(output.energy_drift(), clock.limited_steps(),
                                     step_count, t);
    }
    if (last)
    {
      TimerOutput::Scope scope(timer, "output");
      output.write_final(step_count, t);
      output.report_progress(start, step_count, 1.0, t);
      return;
    }
    if (checkpoint_due(last_checkpoint))
    {
      TimerOutput::Scope scope(timer, "checkpoint");
      write_checkpoint();
      last_checkpoint = std::chrono::steady_clock::now();
    }
    if (step_count % report_every == 0)
      output.report_progress(start, step_count, std::min(1.0, t / clock.end_time()), t);
    guard.stop_if_interrupted(interrupt_signal, step_count, t);
    const unsigned int max_steps = parts.parameters.max_steps;
    if (max_steps > 0 && step_count >= max_steps)
      AssertThrow(false, ExcStepLimit(step_count, t));
  }
}

template <int dim>
std::string Simulation<dim>::end_failed_run(const std::exception &e)
{
  // Called while the exception is handled: an error on one rank only (the others
  // wait in a collective call) goes on to the program, which stops every rank
  // (main.cc); writing output here would hang.
  const bool on_all_ranks = dynamic_cast<const ExcRunAborted *>(&e) != nullptr ||
                            dynamic_cast<const ExcRunStopped *>(&e) != nullptr ||
                            dynamic_cast<const ExcStepLimit *>(&e) != nullptr ||
                            dynamic_cast<const ExcInterrupted *>(&e) != nullptr;
  const bool step_failed = dynamic_cast<const ExcStepFailedOnAllRanks *>(&e) != nullptr;
  if (parts.ranks.distributed() && !on_all_ranks && !step_failed)
    throw;
  std::string message = input::concise_message(e);
  if (!on_all_ranks)
  {
    // A file that could not be written belongs to the step done, not the next.
    const bool writing = dynamic_cast<const ExcCannotWrite *>(&e) != nullptr;
    std::ostringstream where;
    where << "Run stopped at step " << step_count + (writing ? 0 : 1) << ", time " << t
          << (writing ? ", writing its output: " : ": ") << message;
    message = where.str();
  }
  // Keep what the run produced: one last row and particle file at the failure
  // (unless this step's are written already).
  try
  {
    output.write_final(step_count, t);
  }
  catch (...)
  {
  }
  return message;
}

template <int dim>
void Simulation<dim>::write_summary(const RunSummary &summary,
                                    const std::uint64_t checksum, std::string &status,
                                    std::string &message) const
{
  const std::string file = output.directory() + "/summary.json";
  try
  {
    summary.write(file, parts.shape_function->name(), checksum, dim);
  }
  catch (const std::exception &e)
  {
    // A full disk: no summary at all rather than an earlier run's (doc/outputs.md).
    std::remove(file.c_str());
    fail_on_write(input::concise_message(e), status, message);
  }
}

template <int dim>
void Simulation<dim>::fail_on_write(const std::string &why, std::string &status,
                                    std::string &message)
{
  // A run that ended well fails for the file it could not write; one that failed
  // already keeps its own cause first.
  if (status == "completed" || status == "stopped")
    status = "aborted", message = why;
  else
    message += "; also " + why;
}

template <int dim>
std::map<std::string, double> Simulation<dim>::run()
{
  TimerOutput timer(output.console(), TimerOutput::never, TimerOutput::wall_times);
  const auto start = std::chrono::steady_clock::now();
  try
  {
    output.prepare(resumed, clock);
  }
  catch (const ExcCannotWrite &)
  {
    // Nothing of this run is written: no summary either, not even a resumed one's.
    if (output.writes_files())
      std::remove((output.directory() + "/summary.json").c_str());
    throw;
  }
  std::string status = "completed", message, stop_reason;
  try
  {
    advance_to_end(timer, start);
    if (!output.stop_reason().empty())
    {
      status      = "stopped";
      stop_reason = "scene";
    }
  }
  catch (const ExcStepLimit &e)
  {
    // A trial run that asked for fewer steps: it ends as planned, not as an error.
    status      = "stopped";
    stop_reason = "Time/Maximum steps";
    message     = end_failed_run(e);
  }
  catch (const ExcInterrupted &e)
  {
    // The step is complete: keep its row and, where checkpoints are on, a checkpoint
    // of it to go on from.
    status = "interrupted";
    // The checkpoint before the row end_failed_run() adds: a resumed run cuts that
    // row, and its history is the uninterrupted run's.
    std::string checkpoint_failure;
    if (checkpoints_on())
      try
      {
        write_checkpoint();
      }
      catch (const ExcCannotWrite &failure)
      {
        checkpoint_failure = input::concise_message(failure);
      }
    message = end_failed_run(e);
    if (!checkpoint_failure.empty())
      fail_on_write(checkpoint_failure, status, message);
    else if (checkpoints_on())
      message +=
          "; checkpoint written: continue with lme-mpm --resume " + output.directory();
    else
      message += "; no checkpoint (Checkpoint/Every steps and Every seconds are 0): "
                 "the run cannot be continued";
  }
  catch (const std::exception &e)
  {
    // Any failure inside the loop (an unstable step, a shape-function solve that does
    // not converge) ends the run with what it produced kept on disk.
    status  = "aborted";
    message = end_failed_run(e);
  }
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string status_at_end = status;
  RunSummary summary              = output.summarise(wall, step_count, clock, t);
  if (!output.failed_end_file().empty())
    fail_on_write(output.failed_end_file(), status, message);
  summary.status               = status;
  summary.stop_reason          = status == "stopped" ? stop_reason : "";
  summary.message              = message.empty() ? output.stop_reason() : message;
  const std::uint64_t checksum = state_checksum();
  if (output.writes_files())
    write_summary(summary, checksum, status, message);
  // Past this point the output is on disk (on every rank); the caller reports the
  // failure. A file that rank 0 alone writes and could not fails every rank alike.
  if (parts.ranks.max(status == status_at_end ? 0.0 : 1.0) > 0)
  {
    if (status == status_at_end)
      fail_on_write("", status, message);
    message = parts.ranks.broadcast(message);
  }
  // Every rank ends alike; main() tells this from an error on one rank only.
  AssertThrow(status != "interrupted", ExcRunInterrupted(message));
  AssertThrow(status == "completed" || status == "stopped", ExcRunFailed(message));
  if (status == "stopped" && !message.empty())
    output.console() << message << std::endl;
  timer.print_summary();
  output.report_end(wall, step_count, stepper.exchange_seconds());
  return summary.values;
}

template class Simulation<2>;
template class Simulation<3>;
} // namespace lme_mpm
