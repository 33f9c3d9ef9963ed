#include <lme_mpm/base/file_writing.h>
#include <lme_mpm/base/format.h>
#include <lme_mpm/base/input.h>
#include <lme_mpm/base/memory.h>
#include <lme_mpm/output/run_files.h>
#include <lme_mpm/simulation/run_output.h>

#include <fstream>

#include <filesystem>
#include <iomanip>
#include <numeric>
#include <sstream>
#include <system_error>

namespace lme_mpm
{
template <int dim>
RunOutput<dim>::RunOutput(const SimulationParts<dim> &parts, const StageTimer &stages,
                          std::ostream &console)
    : parts(parts), stages(stages), pcout(console, false)
{
  add_columns();
}

template <int dim>
void RunOutput<dim>::add_columns()
{
  const auto &p = parts;
  columns.push_back(
      {[](std::ostream &out)
       {
         out << ",";
         EnergyBalance<dim>::write_header(out);
       },
       [this](std::ostream &out, const ParticleStore<dim> &all, double)
       {
         // Every particle, summed as on one rank (the drift is tracked every step).
         const Energies e = energy.measure(all, parts.materials);
         out << ",";
         EnergyBalance<dim>::write_row(out, e);
         results["final_total_energy"]   = e.total();
         results["final_kinetic_energy"] = e.kinetic;
         results["final_strain_energy"]  = e.strain;
       },
       [this](std::map<std::string, double> &r, const ParticleStore<dim> &all, double)
       {
         // Before the scene's results, which may compare with it.
         if (parts.fracture.active())
           r["dissipated_energy"] = energy.measure(all, parts.materials).dissipated;
       }});
  columns.push_back({[this](std::ostream &out) { fast_particles.write_header(out); },
                     [this](std::ostream &out, const ParticleStore<dim> &, double)
                     { fast_particles.write_row(out); },
                     nullptr});
  columns.push_back({[&p](std::ostream &out) { p.constraints.write_header(out); },
                     [&p](std::ostream &out, const ParticleStore<dim> &, double)
                     { p.constraints.write_row(out); },
                     [this](std::map<std::string, double> &r, const ParticleStore<dim> &,
                            double) { peak_force.add_results(r); }});
  columns.push_back(
      {[&p](std::ostream &out) { p.bodies.write_header(out, p.contact_forces()); },
       [this](std::ostream &out, const ParticleStore<dim> &all, double)
       {
         // The contact forces' means over the force window and over the interval
         // this row closes.
         contact_means.close_row(body_forces());
         const bool contact = parts.contact_forces();
         parts.bodies.write_row(out, all, contact ? &contact_means.current() : nullptr,
                                &contact_means.mean(), &parts.rigid.displacements());
       },
       [this](std::map<std::string, double> &r, const ParticleStore<dim> &, double)
       {
         if (parts.contact_forces())
           for (unsigned int b = 0; b < parts.bodies.size(); ++b)
             if (!parts.bodies.name(b).empty())
               r["peak_contact_force_" + parts.bodies.name(b)] = contact_means.peak()[b];
         parts.contact.add_results(r);
         parts.rigid.add_results(r);
       }});
  columns.push_back(
      {[&p](std::ostream &out)
       {
         p.gauges.write_header(out);
         p.control.write_header(out);
         p.mass.write_header(out);
       },
       [&p](std::ostream &out, const ParticleStore<dim> &all, double)
       {
         p.gauges.write_row(out, all);
         p.control.write_row(out);
         p.mass.write_row(out);
       },
       [this](std::map<std::string, double> &r, const ParticleStore<dim> &, double)
       {
         parts.control.add_results(r);
         parts.mass.add_results(r);
         load_test.add_results(r);
       }});
  columns.push_back({[this](std::ostream &out) { probes.write_header(out); },
                     [this](std::ostream &out, const ParticleStore<dim> &all, double)
                     { probes.write_row(out, all); },
                     {}});
  columns.push_back(
      {[&p](std::ostream &out) { p.scene->write_history_header(out); },
       [this](std::ostream &out, const ParticleStore<dim> &all, const double t)
       { parts.scene->write_history_row(out, scene_state(t, all)); },
       [this](std::map<std::string, double> &r, const ParticleStore<dim> &all,
              const double t) { parts.scene->add_results(scene_state(t, all), r); }});
  columns.push_back({[this](std::ostream &out) { exact.write_header(out); },
                     [this](std::ostream &out, const ParticleStore<dim> &all,
                            const double t) { exact.write_row(out, all, t); },
                     [this](std::map<std::string, double> &r, const ParticleStore<dim> &,
                            double) { exact.add_results(r); }});
}

template <int dim>
void RunOutput<dim>::declare_parameters(ParameterHandler &prm,
                                        const unsigned int n_probes)
{
  Probes<dim>::declare_parameters(prm, n_probes);
  OpeningGauges<dim>::declare_parameters(prm);
  ExactSolution<dim>::declare_parameters(prm);
}

template <int dim>
void RunOutput<dim>::parse_parameters(ParameterHandler &prm, const unsigned int n_probes)
{
  pcout.set_condition(parts.parameters.verbosity > 0 && parts.ranks.rank() == 0);
  if (parts.bodies.any_prescribed())
    energy.set_excluded_bodies(parts.bodies.prescribed_flags());
  peak_force.parse(parts.parameters.peak_force_set, parts.constraints);
  load_test.set_active(parts.control.has_devices() && parts.contact_forces());
  contact_means.reset(parts.bodies.size(), parts.parameters.force_window);
  probes.parse_parameters(prm, n_probes);
  exact.parse_parameters(prm);
  open(parts.parameters.directory);
}

template <int dim>
void RunOutput<dim>::open(const std::string &directory)
{
  output_directory = directory;
  particle_output =
      std::make_unique<ParticleOutput<dim>>(directory, parts.parameters.thickness);
  grid_output = std::make_unique<GridOutput<dim>>(directory);
}

template <int dim>
const ParticleStore<dim> &RunOutput<dim>::observed() const
{
  if (!parts.ranks.distributed())
    return parts.particles;
  parts.ranks.gather(parts.particles, gathered);
  return gathered;
}

template <int dim>
SceneState<dim> RunOutput<dim>::scene_state(const double t,
                                            const ParticleStore<dim> &particles) const
{
  SceneState<dim> state;
  state.particles   = &particles;
  state.body_names  = &parts.bodies.names();
  state.run         = &parts.parameters;
  state.constraints = &parts.constraints;
  state.gauges      = &parts.gauges;
  state.grid        = &parts.grid;
  if (parts.contact_forces())
  {
    state.contact_forces      = &contact_means.current();
    state.peak_contact_forces = &contact_means.peak();
    state.contact_force_means = &contact_means.mean();
  }
  state.time         = t;
  state.force_window = parts.parameters.force_window;
  return state;
}

template <int dim>
SceneState<dim> RunOutput<dim>::step_state(const double t, const double dt) const
{
  SceneState<dim> state     = scene_state(t, parts.particles);
  state.contact_force_means = nullptr;
  state.ranks               = &parts.ranks;
  state.step_length         = dt;
  state.all_particles = [this]() -> const ParticleStore<dim> & { return observed(); };
  return state;
}

template <int dim>
void RunOutput<dim>::prepare(const bool resumed, const TimeStepControl &clock)
{
  const RunParameters<dim> &run = parts.parameters;
  unsigned int removed          = 0;
  exact.compute_norms(observed(), run.end_time);
  // Only now, with every input checked, does the run write anything (rank 0 makes
  // the directory the others write their pieces to).
  if (writes_files())
  {
    std::error_code ec;
    std::filesystem::create_directories(output_directory, ec);
    AssertThrow(!ec,
                ExcBadInput("Output/Directory",
                            "cannot create '" + output_directory + "': " + ec.message()));
    // A new run does not write beside another run's files (doc/outputs.md).
    if (!resumed)
      removed = remove_earlier_run(output_directory);
  }
  parts.ranks.barrier();
  if (!writes_files())
    return;
  if (!record.parameters.empty())
    files::write_atomically(output_directory + "/parameters.prm", record.parameters);
  if (resumed)
    history.resume(output_directory, resumed_history_size);
  else
  {
    std::ostringstream header;
    header << "step,time";
    for (const auto &c : columns)
      c.header(header);
    history.create(output_directory, header.str());
  }
  pcout << "lme-mpm: " << dim << "D, " << n_particles << " particles, "
        << parts.grid.n_nodes() << " nodes, shape functions '"
        << parts.shape_function->name() << "', dt = " << clock.wave_step() << " s, "
        << clock.planned_steps() << " steps"
        << (run.particle_travel > 0 ? " (more while particles travel fast)" : "") << ", "
        << parts.transfer.threads() << " thread(s)" << std::endl;
  for (const auto &w : parts.materials.input_warnings())
    pcout << "lme-mpm: warning: " << w << std::endl;
  if (removed > 0)
    pcout << "lme-mpm: removed " << removed << " files of an earlier run from '"
          << output_directory << "'" << std::endl;
}

template <int dim>
const std::vector<Tensor<1, dim>> &RunOutput<dim>::body_forces()
{
  if (!parts.rigid.active())
    return parts.contact.step_forces();
  const auto &a = parts.contact.step_forces(), &b = parts.rigid.step_forces();
  force_sum.resize(b.size());
  for (std::size_t i = 0; i < b.size(); ++i)
    force_sum[i] = (i < a.size() ? a[i] : Tensor<1, dim>()) + b[i];
  return force_sum;
}

template <int dim>
void RunOutput<dim>::after_step(const double external_work, const double dt,
                                const double t, const double max_speed)
{
  if (fast_particles.observe(max_speed))
    pcout << "lme-mpm: warning at t = " << t << ": " << fast_particles.warning()
          << std::endl;
  energy.add_external_work(external_work);
  const Energies e = energy.measure(parts.particles, parts.materials, parts.ranks);
  energy.track(e, false);
  peak_force.update(parts.constraints);
  // Every step counts towards the contact forces' means, with contact or not.
  contact_means.book(body_forces(), dt);
  if (load_test.active())
    load_test.observe(parts.control.device_load(contact_means.current(), t), e, t);
  const SceneState<dim> state = step_state(t, dt);
  parts.scene->observe(state);
  std::string reason = parts.scene->finished(state);
  // Every rank ends the run together (a scene judges on reduced values; should one
  // not, the first rank's words are kept).
  if (parts.ranks.distributed() && parts.ranks.max(reason.empty() ? 0.0 : 1.0) > 0)
  {
    reason = parts.ranks.broadcast(reason);
    if (reason.empty())
      reason = "the scene's stop rule";
  }
  if (!reason.empty() && scene_stop.empty())
  {
    scene_stop = reason;
    pcout << "Stopped at t = " << t << ": " << reason << std::endl;
  }
}

template <int dim>
double RunOutput<dim>::file_interval(const bool on, const double interval) const
{
  if (!on)
    return std::numeric_limits<double>::max();
  return interval > 0 ? interval : parts.parameters.output_interval;
}

template <int dim>
void RunOutput<dim>::write_first_row(const double t)
{
  energy.track(energy.measure(parts.particles, parts.materials, parts.ranks), true);
  write_final(0, t);
  const RunParameters<dim> &run = parts.parameters;
  next_time                     = run.output_interval;
  next_particle_time = file_interval(run.write_particles, run.particle_interval);
  next_grid_time     = file_interval(run.write_grid, run.grid_interval);
}

template <int dim>
void RunOutput<dim>::write_due_row(const unsigned int step, const double t,
                                   const double dt)
{
  const RunParameters<dim> &run = parts.parameters;
  // The first output time past this step (an interval below the rounding of t
  // would never move it by addition).
  const auto advance = [&](double &next, const double interval)
  {
    if (t < next - 0.5 * dt)
      return false;
    next = interval * (std::floor((t + 0.5 * dt) / interval) + 1);
    return true;
  };
  const bool row       = advance(next_time, run.output_interval);
  const bool particles = advance(
      next_particle_time, file_interval(run.write_particles, run.particle_interval));
  const bool grid =
      advance(next_grid_time, file_interval(run.write_grid, run.grid_interval));
  write_outputs(step, t, row, particles, grid);
}

template <int dim>
void RunOutput<dim>::write_final(const unsigned int step, const double t)
{
  const RunParameters<dim> &run = parts.parameters;
  const auto missing            = [&](const bool any, const unsigned int last)
  { return !any || last != step; };
  write_outputs(step, t, missing(any_row, row_step),
                run.write_particles && missing(any_particle_file, particle_step),
                run.write_grid && missing(any_grid_file, grid_step));
}

template <int dim>
void RunOutput<dim>::write_outputs(const unsigned int step, const double t,
                                   const bool row, const bool particles, const bool grid)
{
  // A distributed run reads every particle on rank 0, which writes the files; each
  // rank writes its own particles' piece.
  const bool distributed = parts.ranks.distributed();
  if (row)
    row_step = step, any_row = true;
  if (particles)
    particle_step = step, any_particle_file = true;
  if (grid)
    grid_step = step, any_grid_file = true;
  if (grid && distributed)
    write_grid_file(t);
  if (particles && distributed)
    particle_output->write_piece(parts.particles, t, parts.ranks.rank(),
                                 parts.ranks.n_ranks());
  const ParticleStore<dim> *all = row ? &observed() : nullptr;
  if (!writes_files())
    return;
  if (row)
  {
    std::ostringstream text;
    text << std::setprecision(10) << step << "," << t;
    for (const auto &c : columns)
      c.row(text, *all, t);
    history.write_row(text.str());
  }
  if (particles && !distributed)
    particle_output->write(parts.particles, t);
  if (grid && !distributed)
    grid_output->write(parts.grid, parts.transfer.nodes().mass,
                       parts.transfer.nodes().rate, t);
}

template <int dim>
void RunOutput<dim>::write_grid_file(const double t)
{
  // Each node from the rank that owns it (elsewhere its sums miss particles): masses
  // and rates in one message.
  const unsigned int n          = parts.grid.n_nodes();
  const NodalFields<dim> &nodes = parts.transfer.nodes();
  std::vector<double> values(n * (1 + dim), 0.0);
  for (unsigned int I = 0; I < n && I < nodes.mass.size(); ++I)
    if (parts.ranks.owns_node(I))
    {
      values[I] = nodes.mass[I];
      for (unsigned int d = 0; d < dim; ++d)
        values[n + I * dim + d] = nodes.rate[I][d];
    }
  parts.ranks.sum(values);
  if (!writes_files())
    return;
  std::vector<double> mass(values.begin(), values.begin() + n);
  std::vector<Tensor<1, dim>> rate(n);
  for (unsigned int I = 0; I < n; ++I)
    for (unsigned int d = 0; d < dim; ++d)
      rate[I][d] = values[n + I * dim + d];
  grid_output->write(parts.grid, mass, rate, t);
}

template <int dim>
std::map<std::string, double> RunOutput<dim>::energies() const
{
  return energy.measure(observed(), parts.materials).as_map();
}

template <int dim>
void RunOutput<dim>::record_totals()
{
  const ParticleStore<dim> &p = parts.particles;
  n_particles                 = p.size();
  initial_mass                = std::accumulate(p.mass.begin(), p.mass.end(), 0.0);
  // Each body's volume as its particles hold it: what a body read from a mesh or a
  // particle file is checked by.
  body_volumes.clear();
  for (const auto &name : parts.bodies.names())
    body_volumes.emplace_back(name, 0.0);
  for (std::size_t i = 0; i < p.size(); ++i)
    body_volumes[p.body_id[i]].second += p.initial_volume[i];
  fast_particles.set_up(
      parts.shape_function->name(), parts.grid.min_spacing(),
      parts.materials.max_wave_speed(),
      FastParticles::transit_length(p, parts.bodies.prescribed_flags()));
}

template <int dim>
RunSummary RunOutput<dim>::summarise(const double wall, const unsigned int steps,
                                     const TimeStepControl &clock, const double t)
{
  // Every rank takes part in the gathering; rank 0 summarises.
  const ParticleStore<dim> &all = observed();
  const double peak_resident    = parts.ranks.max(memory::peak_resident_bytes());
  RunSummary summary;
  if (!writes_files())
    return summary;
  summary.record                       = record;
  summary.record.parameters            = "";
  results["wall_seconds"]              = wall;
  results["steps"]                     = steps;
  results["particles"]                 = n_particles;
  results["ranks"]                     = parts.ranks.n_ranks();
  results["nodes"]                     = parts.grid.n_nodes();
  results["threads"]                   = parts.transfer.threads();
  results["time_step"]                 = clock.wave_step();
  results["smallest_time_step"]        = clock.smallest_step();
  results["travel_limited_steps"]      = clock.limited_steps();
  results["particle_steps_per_second"] = n_particles * double(steps) / wall;
  results["peak_resident_megabytes"]   = peak_resident / 1e6; // largest of the ranks
  if (const auto [changed, sorts] = parts.transfer.reorders(); sorts > 0)
    results["particle_reorder_share"] = double(changed) / sorts;
  results["max_energy_drift"]          = energy.max_drift();
  results["max_fast_particle_cells"]   = fast_particles.max();
  results["max_energy_drift_absolute"] = energy.max_absolute_drift();
  results["energy_scale"]              = energy.scale();
  stages.add_results(results);
  for (const auto &c : columns)
    if (c.results)
      c.results(results, all, t);
  {
    // Against G_F times the crack's area, which a scene's fracture_energy_ratio
    // divides the dissipated energy by.
    const auto w = results.find("work_of_fracture"),
               d = results.find("dissipated_energy"),
               f = results.find("fracture_energy_ratio");
    if (w != results.end() && d != results.end() && f != results.end() && d->second > 0)
      results["work_of_fracture_ratio"] = w->second * f->second / d->second;
  }
  for (const auto &s : parts.shape_function->statistics())
    results["shape_function_" + s.first] = s.second;
  // What the ranks hold now, against what the run started with (migration must
  // neither lose nor copy a particle).
  results["final_particles"] = all.size();
  results["final_mass"]      = std::accumulate(all.mass.begin(), all.mass.end(), 0.0);
  results["initial_mass"]    = initial_mass;
  for (const auto &v : body_volumes)
    if (!v.first.empty() && v.second > 0) // not a rigid exact surface
      results["initial_volume_" + v.first] = v.second;
  parts.fracture.add_statistics(all, results);
  if (!parts.cracks.empty())
    results["crack_second_fields"] = parts.cracks.n_crack_nodes();
  try
  {
    if (parts.fracture.active())
    {
      write_failed_particles(output_directory + "/failed_particles.csv", all);
      write_damage_field(output_directory + "/damage.csv", all);
    }
    if (!parts.cracks.empty())
      write_polylines(output_directory + "/cracks.csv", parts.cracks.polylines());
  }
  catch (const std::exception &e)
  {
    // summary.json still gets written, with this as the run's failure.
    end_file_failure = input::concise_message(e);
  }
  summary.values   = results;
  summary.warnings = parts.materials.input_warnings();
  if (!fast_particles.warning().empty())
    summary.warnings.push_back(fast_particles.warning());
  return summary;
}

template <int dim>
void RunOutput<dim>::report_progress(const std::chrono::steady_clock::time_point start,
                                     const unsigned int step, const double done,
                                     const double t)
{
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  pcout << "  step " << std::setw(8) << step << "  t = " << std::setw(12)
        << std::setprecision(5) << t << "  " << std::setw(3)
        << static_cast<int>(100 * done + 1e-9) << "%  " << std::setprecision(3)
        << n_particles * step / elapsed << " particle-steps/s  ETA "
        << std::setprecision(3) << elapsed * (1 - done) / std::max(done, 1e-12) << " s"
        << std::endl;
}

template <int dim>
void RunOutput<dim>::report_balance(const double wall, const double exchange_seconds)
{
  const Decomposition<dim> &ranks = parts.ranks;
  if (!ranks.distributed())
    return;
  // What each rank holds at the end, and how long its exchanges took (waiting for
  // the slowest rank included): tells an uneven split from a costly halo.
  const std::size_t owned = Decomposition<dim>::n_owned(parts.particles);
  const auto owned_all    = ranks.all_gather(static_cast<double>(owned));
  const auto ghosts_all =
      ranks.all_gather(static_cast<double>(parts.particles.size() - owned));
  const auto exchange_all = ranks.all_gather(exchange_seconds);
  for (unsigned int r = 0; r < ranks.n_ranks(); ++r)
    pcout << "rank " << r << ": " << owned_all[r] << " particles, " << ghosts_all[r]
          << " ghosts; exchange " << exchange_all[r] << " s of " << wall << " s"
          << std::endl;
}

template <int dim>
void RunOutput<dim>::report_end(const double wall, const unsigned int steps,
                                const double exchange_seconds)
{
  if (pcout.is_active())
    stages.print(pcout.get_stream(), wall);
  report_balance(wall, exchange_seconds);
  const auto rate = results.find("particle_steps_per_second");
  pcout << "Finished: " << steps << " steps in " << wall << " s ("
        << (rate == results.end() ? 0.0 : rate->second)
        << " particle-steps/s); max energy drift " << energy.max_drift() << std::endl;
}

template <int dim>
void RunOutput<dim>::serialize_parameters(Archive &ar)
{
  std::string saved = record.parameters;
  ar(saved);
  if (!ar.loading() || record.parameters.empty() || saved.empty())
    return;
  const std::string changed = first_changed_entry(saved, record.parameters);
  AssertThrow(changed.empty(),
              ExcBadInput("--resume",
                          "the checkpoint was written with other parameters (" + changed +
                              "): resume with the parameter file and --set "
                              "values of the run that wrote it"));
}

template <int dim>
void RunOutput<dim>::serialize(Archive &ar)
{
  energy.serialize(ar);
  ar(next_time, next_particle_time, next_grid_time);
  ar(row_step, particle_step, grid_step, any_row, any_particle_file, any_grid_file);
  peak_force.serialize(ar);
  fast_particles.serialize(ar);
  contact_means.serialize(ar);
  AssertThrow(contact_means.peak().size() == parts.bodies.size(),
              ExcMessage("the checkpoint holds another number of bodies"));
  exact.serialize(ar);
  load_test.serialize(ar);
  // Only rank 0 writes history.csv.
  std::uint64_t history_size = ar.loading() || !writes_files() ? 0 : history.size();
  ar(history_size);
  if (ar.loading())
    resumed_history_size = history_size;
  auto particle_series = particle_output->series();
  auto grid_series     = grid_output->series();
  ar(particle_series, grid_series);
  if (ar.loading())
  {
    particle_output->restore(particle_series);
    grid_output->restore(grid_series);
  }
}

template class RunOutput<2>;
template class RunOutput<3>;
} // namespace lme_mpm
