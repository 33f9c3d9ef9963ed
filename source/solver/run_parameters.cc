#include <lme_mpm/base/input.h>
#include <lme_mpm/solver/run_parameters.h>

#include <unistd.h>

#include <filesystem>
#include <system_error>

#include <cmath>
#include <sstream>

namespace lme_mpm
{
void ParameterCounts::entries(EntryList &list)
{
  list.enter("Problem");
  list.add("Dimension", dim, "2", Patterns::Integer(2, 3), "Space dimension, 2 or 3.");
  list.add("Number of materials", materials, "1", Patterns::Integer(1, 64),
           "How many 'Material N' subsections follow.");
  list.add("Number of bodies", bodies, "1", Patterns::Integer(1, 64),
           "How many 'Body N' subsections follow.");
  list.leave();
  list.enter("Boundary conditions");
  list.add("Number of constraints", constraints, "0", Patterns::Integer(0, 64),
           "How many 'Constraint N' subsections follow.");
  list.leave();
  list.enter("Output");
  list.add("Number of probes", probes, "0", Patterns::Integer(0, 64),
           "How many 'Probe N' subsections follow.");
  list.leave();
}

void ParameterCounts::declare_parameters(ParameterHandler &prm)
{
  EntryList list(prm, EntryList::Mode::declare);
  ParameterCounts().entries(list);
}

void ParameterCounts::parse_parameters(ParameterHandler &prm)
{
  EntryList list(prm, EntryList::Mode::parse);
  entries(list);
}

template <int dim>
void RunParameters<dim>::time_entries(EntryList &list)
{
  list.enter("Time");
  list.add("End time", end_time, "1", Patterns::Double(0), "Simulated time (s), > 0.");
  list.add("CFL", cfl, "0.3", Patterns::Double(0),
           "Time step as a fraction of h_min / c_P (c_P the fastest P-wave "
           "speed). Used when 'Time step' is 0.");
  list.add("Time step", fixed_time_step, "0", Patterns::Double(0),
           "Fixed time step (s); 0 takes it from the CFL number.");
  list.add("Maximum CFL", max_cfl, "1", Patterns::Double(0, 2),
           "Largest accepted ratio dt c_P / h_min; a larger CFL or fixed time "
           "step is rejected (explicit schemes are unstable beyond about 1).");
  list.add("Mass matrix corrections", mass_corrections, "0", Patterns::Integer(0, 10),
           "Jacobi corrections of the lumped-mass solves towards the consistent "
           "mass matrix sum_p m_p N_Ip N_Jp (each costs two grid transfers). 0 is "
           "the lumped mass of standard MPM and of the paper; 1-2 remove most of "
           "the lumping's phase error, which grows with the support width "
           "(doc/shape_functions.md).");
  list.add("Mass matrix", mass_matrix, "lumped", Patterns::Selection("lumped|consistent"),
           "The mass matrix of the grid's two solves per step. 'lumped' (the paper's, "
           "with 'Mass matrix corrections' Jacobi corrections towards the consistent "
           "one); 'consistent': M_C = sum_p m_p N_Ip N_Jp of each body's field, "
           "assembled each step as a Trilinos matrix and solved by conjugate gradients "
           "preconditioned with the lumped mass, from the lumped solution, to "
           "'Consistent mass tolerance' (any number of MPI ranks; "
           "doc/shape_functions.md).");
  list.add("Consistent mass tolerance", consistent_mass_tolerance, "1e-10",
           Patterns::Double(0),
           "Mass matrix = consistent: the solve stops when the residual's norm weighted "
           "by the inverse lumped mass falls below this fraction of the right-hand "
           "side's, in (0, 0.1).");
  list.add("Consistent mass iterations", consistent_mass_iterations, "1000",
           Patterns::Integer(1, 10000),
           "Mass matrix = consistent: the most iterations a solve may take; a solve "
           "that has not reached its tolerance by then stops the run.");
  list.add("Newmark gamma", newmark_gamma, "0.5", Patterns::Double(0.5, 1),
           "Newmark gamma in [0.5, 1]: 0.5 conserves energy (second order), "
           "larger values damp high frequencies (first order).");
  list.add("Particle travel per step", particle_travel, "0.01", Patterns::Double(0, 0.5),
           "Largest distance a particle may travel in one step, as a fraction of the "
           "smallest cell: the step is shortened below the CFL step whenever the "
           "fastest particle would go further (evaluated every step, so slow runs "
           "are not affected). The explicit update holds the shape functions of "
           "the start of the step for the whole step, and its energy error grows "
           "with this travel (doc/stability.md): 0.01 keeps a bar vibrating at a "
           "tenth of its wave speed within 0.1 % of its energy over three periods "
           "with B-splines and LME. 0: no limit.");
  list.add("Particle update", particle_update, "flip", Patterns::Selection("flip|xpic"),
           "How the particles' velocities follow the grid: 'flip' adds the grid's "
           "acceleration to each particle's own velocity (no numerical dissipation, "
           "keeps velocity modes the grid cannot see); 'xpic' is XPIC(m) of "
           "Hammerquist & Nairn (2017), which drops those modes and keeps the "
           "grid-representable velocity to order m (m = 1 is PIC).");
  list.add("XPIC order", xpic_order_entry, "2", Patterns::Integer(1, 10),
           "The order m of the XPIC update (each order above 1 costs two grid "
           "transfers per step). Used with Particle update = xpic.");
  list.add("Maximum steps", max_steps, "0", Patterns::Integer(0),
           "Stop after this many steps (0: no limit), for a trial of a scene's "
           "set-up; such a run ends with status 'stopped' (stop_reason 'Time/Maximum "
           "steps') and exit code 0.");
  list.leave();
}

template <int dim>
void RunParameters<dim>::entries(EntryList &list)
{
  list.enter("Problem");
  list.add("Thickness", thickness, "1", Patterns::Double(0),
           "Out-of-plane thickness of a 2D specimen (m); masses, forces and "
           "energies are those of the specimen. Ignored in 3D.");
  list.add("Plane assumption", plane_assumption, "plane strain",
           Patterns::Selection("plane strain|plane stress"),
           "How a 2D model treats the out-of-plane direction.");
  list.add("Units", units, "SI", Patterns::Selection("SI|unitless"),
           "The units of the file's numbers. 'SI': a material entry outside the "
           "range physical for solids (Young's modulus 1e3 to 1e13 Pa, density 1 to "
           "1e5 kg/m^3) is named in a warning. 'unitless': a scaled problem (the "
           "mode-I panel), whose values no range applies to.");
  list.add("Body force", body_force_text, "0, 0, 0", Patterns::Anything(),
           "Body force per unit mass (m/s^2), dim components (extra ones "
           "ignored), for example '0, -9.81'.");
  list.add("Body force ramp time", body_force_ramp, "0", Patterns::Double(0),
           "The body force grows linearly from zero to its full value over this "
           "time (s): a load applied over many periods of the specimen's slowest "
           "vibration starts it quasi-statically, where a sudden one sets it ringing. "
           "0: in full from the start.");
  list.leave();

  time_entries(list);

  list.enter("Output");
  list.add("Directory", directory, "output", Patterns::Anything(),
           "Directory for VTU/PVD files, history.csv and summary.json.");
  list.add("Output interval", output_interval, "0", Patterns::Double(0),
           "Simulated time between history.csv rows (s), and between particle and "
           "grid files unless their own intervals are given; 0: 20 per run. Results "
           "in summary.json do not depend on it: peaks, their times, stop rules and "
           "the energy drift are checked every step.");
  list.add("Particle file interval", particle_interval, "0", Patterns::Double(0),
           "Simulated time between particle files (s); 0: the Output interval.");
  list.add("Grid file interval", grid_interval, "0", Patterns::Double(0),
           "Simulated time between grid files (s); 0: the Output interval.");
  list.add("Force window", force_window, "0", Patterns::Double(0),
           "The contact forces (and the loads scenes derive from them) are judged by "
           "their mean over this much simulated time before each step (s), updated "
           "every step (nothing acts before t = 0): a single step's force chatters as "
           "particles cross cells, and an impact's first step is one impulse. "
           "0: ten times the time a P-wave takes to cross the smallest cell, 10 "
           "h_min / c_P. A window shorter than the time step keeps each step's own "
           "force.");
  list.add("Write particle files", write_particles, "true", Patterns::Bool(),
           "Write particle VTU files (history.csv and summary.json always).");
  list.add("Write grid files", write_grid, "false", Patterns::Bool(),
           "Also write the background grid with nodal velocity and mass.");
  list.add("Peak force set", peak_force_set, "", Patterns::Anything(),
           "Name of a constrained node set and a component, 'top:y': summary.json "
           "then reports peak_force (the reaction of largest magnitude along that "
           "component, checked every step, with its sign) and displacement_at_peak "
           "(the set's imposed displacement then).");
  list.add("Verbosity", verbosity, "1", Patterns::Integer(0, 2),
           "0: errors only; 1: progress and timing; 2: more.");
  list.leave();

  list.enter("Checkpoint");
  list.add("Every steps", checkpoint_every_steps, "0", Patterns::Integer(0),
           "Write output/checkpoint.bin every this many steps (0: never); the "
           "previous one is kept as checkpoint.bin.prev. --resume DIR continues.");
  list.add("Every seconds", checkpoint_every_seconds, "0", Patterns::Double(0),
           "Also write one when this much wall time has passed since the last "
           "(0: never).");
  list.leave();
}

template <int dim>
void RunParameters<dim>::declare_parameters(ParameterHandler &prm)
{
  EntryList list(prm, EntryList::Mode::declare);
  RunParameters<dim>().entries(list);
}

template <int dim>
void RunParameters<dim>::parse_parameters(ParameterHandler &prm)
{
  EntryList list(prm, EntryList::Mode::parse);
  entries(list);
  peak_force_set = input::trim(peak_force_set);
  AssertThrow(!input::trim(directory).empty(),
              ExcBadInput("Output/Directory", "must not be empty"));
  {
    // Nothing is created before every input is checked: here only the part of the
    // path that exists already is looked at.
    std::error_code ec;
    std::filesystem::path existing = std::filesystem::absolute(directory, ec);
    while (!existing.empty() && !std::filesystem::exists(existing, ec) &&
           existing != existing.parent_path())
      existing = existing.parent_path();
    AssertThrow(std::filesystem::is_directory(existing, ec),
                ExcBadInput("Output/Directory", "cannot create '" + directory + "': '" +
                                                    existing.string() +
                                                    "' is a file, not a directory"));
    AssertThrow(::access(existing.c_str(), W_OK) == 0,
                ExcBadInput("Output/Directory", "cannot create '" + directory + "': '" +
                                                    existing.string() +
                                                    "' is not writable"));
  }
  if (dim == 3)
    thickness = 1.0;
  input::require_range(thickness, 0, 1e300, true, "Problem/Thickness");
  plane_stress = plane_assumption == "plane stress";
  const auto g = input::parse_doubles(body_force_text, "Problem/Body force");
  AssertThrow(g.size() >= dim,
              ExcBadInput("Problem/Body force",
                          "needs at least " + std::to_string(dim) + " components"));
  for (unsigned int d = 0; d < dim; ++d)
    body_force[d] = g[d];
  input::require_range(body_force_ramp, 0, 1e300, false, "Problem/Body force ramp time");
  input::require_range(end_time, 0, 1e300, true, "Time/End time");
  xpic_order      = particle_update == "xpic" ? xpic_order_entry : 0;
  consistent_mass = mass_matrix == "consistent";
  if (consistent_mass)
  {
    input::require_range(consistent_mass_tolerance, 0, 0.1, true,
                         "Time/Consistent mass tolerance");
    AssertThrow(mass_corrections == 0,
                ExcBadInput("Time/Mass matrix corrections",
                            "must be 0 with 'Time/Mass matrix = consistent' (the "
                            "corrections approach the consistent mass; the solve "
                            "reaches it)"));
  }
}

template <int dim>
TimeStepping stable_time_step(const RunParameters<dim> &run, const double h_min,
                              const double c_max,
                              const std::vector<input::EntryValue> &wave_speed_inputs)
{
  TimeStepping ts;
  const double dt_wave = h_min / c_max;
  if (run.fixed_time_step > 0)
  {
    std::ostringstream msg;
    msg << "dt = " << run.fixed_time_step
        << " s exceeds the stability limit 'Time/Maximum CFL' * h_min / "
        << "c_P = " << run.max_cfl * dt_wave << " s (h_min = " << h_min
        << " m, c_P = " << c_max << " m/s)";
    AssertThrow(run.fixed_time_step <= run.max_cfl * dt_wave * (1 + 1e-12),
                ExcBadInput("Time/Time step", msg.str()));
    ts.dt = run.fixed_time_step;
  }
  else
  {
    if (!(run.cfl > 0 && run.cfl <= run.max_cfl))
    {
      std::ostringstream msg;
      msg << "value " << run.cfl << " is outside the allowed range (0, " << run.max_cfl
          << "], whose upper end is 'Time/Maximum CFL' (at most 2; explicit steps are "
          << "unstable beyond about 1, doc/stability.md)";
      throw ExcBadInput("Time/CFL", msg.str());
    }
    ts.dt = run.cfl * dt_wave;
  }
  // Where the wave speed makes the step useless, the entries behind it are named with
  // their values, an unphysical one first and blamed.
  const std::string blamed = wave_speed_inputs.empty() ? "the materials' entries"
                                                       : wave_speed_inputs.front().entry;
  std::ostringstream origin;
  if (!wave_speed_inputs.empty())
    origin << input::describe_entries(wave_speed_inputs) << " give ";
  origin << "the P-wave speed c_P = " << c_max
         << " m/s; with the grid's smallest spacing "
         << "h_min = " << h_min << " m the stable time step is " << ts.dt << " s";
  AssertThrow(std::isfinite(ts.dt) && ts.dt > 0, ExcBadInput(blamed, origin.str()));
  // The step does not depend on the end time, so that a run can be extended: it ends
  // with the first whole step at or past the end time (in at least one step). The
  // count is checked as a double, before it is converted.
  const double steps = std::max(1.0, std::ceil(run.end_time / ts.dt - 1e-9));
  {
    std::ostringstream msg;
    msg << origin.str() << ", and 'Time/End time' = " << run.end_time << " s needs "
        << steps << " steps, more than the 2e9 allowed: check these entries, the grid's "
        << "spacing or the end time";
    AssertThrow(steps < 2e9, ExcBadInput(blamed, msg.str()));
  }
  ts.n_steps = static_cast<unsigned int>(steps);
  return ts;
}

template struct RunParameters<2>;
template struct RunParameters<3>;
template TimeStepping stable_time_step(const RunParameters<2> &, double, double,
                                       const std::vector<input::EntryValue> &);
template TimeStepping stable_time_step(const RunParameters<3> &, double, double,
                                       const std::vector<input::EntryValue> &);
} // namespace lme_mpm
