#include <deal.II/base/multithread_info.h>
#include <deal.II/base/quadrature_lib.h>

#include <lme_mpm/base/input.h>
#include <lme_mpm/base/parallel.h>
#include <lme_mpm/geometry/geometry.h>
#include <lme_mpm/shape_functions/tensor_product.h>
#include <lme_mpm/solver/simulation.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <sstream>

namespace lme_mpm
{
namespace
{
const char *axis[3] = {"x", "y", "z"};

std::string subsection_name(const std::string &kind, const unsigned int i)
{
  return kind + " " + std::to_string(i + 1);
}

/// Parses a ParsedFunction in subsection @p section; a bad expression names its entry.
template <int dim>
void parse_function(ParameterHandler &prm, const std::string &section,
                    Functions::ParsedFunction<dim> &f, const std::string &entry)
{
  prm.enter_subsection(section);
  try
  {
    f.parse_parameters(prm);
    // muparser compiles on first use: evaluate once so a syntax error shows here.
    for (unsigned int c = 0; c < f.n_components; ++c)
      (void)f.value(Point<dim>(), c);
  }
  catch (...)
  {
    prm.leave_subsection();
    AssertThrow(false,
                ExcBadInput(entry + "/Function expression",
                            "not a valid expression of the coordinates and t "
                            "with " +
                                std::to_string(dim) + " components separated by ';'"));
  }
  prm.leave_subsection();
}
} // namespace

// ------------------------------------------------------------------ parameters

void ParameterCounts::declare_parameters(ParameterHandler &prm)
{
  prm.enter_subsection("Problem");
  prm.declare_entry("Dimension", "2", Patterns::Integer(2, 3),
                    "Space dimension, 2 or 3.");
  prm.declare_entry("Number of materials", "1", Patterns::Integer(1, 64),
                    "How many 'Material N' subsections follow.");
  prm.declare_entry("Number of bodies", "1", Patterns::Integer(1, 64),
                    "How many 'Body N' subsections follow.");
  prm.leave_subsection();
  prm.enter_subsection("Boundary conditions");
  prm.declare_entry("Number of constraints", "0", Patterns::Integer(0, 64),
                    "How many 'Constraint N' subsections follow.");
  prm.leave_subsection();
  prm.enter_subsection("Output");
  prm.declare_entry("Number of probes", "0", Patterns::Integer(0, 64),
                    "How many 'Probe N' subsections follow.");
  prm.leave_subsection();
}

void ParameterCounts::parse_parameters(ParameterHandler &prm)
{
  prm.enter_subsection("Problem");
  dim       = prm.get_integer("Dimension");
  materials = prm.get_integer("Number of materials");
  bodies    = prm.get_integer("Number of bodies");
  prm.leave_subsection();
  prm.enter_subsection("Boundary conditions");
  constraints = prm.get_integer("Number of constraints");
  prm.leave_subsection();
  prm.enter_subsection("Output");
  probes = prm.get_integer("Number of probes");
  prm.leave_subsection();
}

template <int dim>
void Simulation<dim>::declare_parameters(ParameterHandler &prm,
                                         const ParameterCounts &counts)
{
  ParameterCounts::declare_parameters(prm);
  prm.enter_subsection("Problem");
  prm.declare_entry("Thickness", "1", Patterns::Double(0),
                    "Out-of-plane thickness of a 2D specimen (m); masses, forces and "
                    "energies are those of the specimen. Ignored in 3D.");
  prm.declare_entry("Plane assumption", "plane strain",
                    Patterns::Selection("plane strain|plane stress"),
                    "How a 2D model treats the out-of-plane direction.");
  prm.declare_entry("Body force", "0, 0, 0", Patterns::Anything(),
                    "Body force per unit mass (m/s^2), dim components (extra ones "
                    "ignored), for example '0, -9.81'.");
  prm.leave_subsection();

  BackgroundGrid<dim>::declare_parameters(prm);
  CrackSet<dim>::declare_parameters(prm);

  prm.enter_subsection("Time");
  prm.declare_entry("End time", "1", Patterns::Double(0), "Simulated time (s), > 0.");
  prm.declare_entry("CFL", "0.3", Patterns::Double(0),
                    "Time step as a fraction of h_min / c_P (c_P the fastest P-wave "
                    "speed). Used when 'Time step' is 0.");
  prm.declare_entry("Time step", "0", Patterns::Double(0),
                    "Fixed time step (s); 0 takes it from the CFL number.");
  prm.declare_entry("Maximum CFL", "1", Patterns::Double(0, 2),
                    "Largest accepted ratio dt c_P / h_min; a larger CFL or fixed time "
                    "step is rejected (explicit schemes are unstable beyond about 1).");
  prm.declare_entry(
      "Mass matrix corrections", "0", Patterns::Integer(0, 10),
      "Jacobi corrections of the lumped-mass solves towards the consistent "
      "mass matrix sum_p m_p N_Ip N_Jp (each costs two grid transfers). 0 is "
      "the lumped mass of standard MPM and of the paper; 1-2 remove most of "
      "the lumping's phase error, which grows with the support width "
      "(doc/shape_functions.md).");
  prm.declare_entry("Newmark gamma", "0.5", Patterns::Double(0.5, 1),
                    "Newmark gamma in [0.5, 1]: 0.5 conserves energy (second order), "
                    "larger values damp high frequencies (first order).");
  prm.leave_subsection();

  prm.enter_subsection("Shape functions");
  prm.declare_entry("Type", "linear",
                    Patterns::Selection(ShapeFunctionRegistry<dim>::instance().pattern()),
                    "Particle-node coupling. " +
                        ShapeFunctionRegistry<dim>::instance().documentation());
  ShapeFunctionRegistry<dim>::instance().declare_all(prm);
  prm.leave_subsection();

  for (unsigned int m = 0; m < counts.materials; ++m)
  {
    prm.enter_subsection(subsection_name("Material", m));
    prm.declare_entry("Model", "linear elastic",
                      Patterns::Selection(MaterialRegistry<dim>::instance().pattern()),
                      "Constitutive model. " +
                          MaterialRegistry<dim>::instance().documentation());
    prm.declare_entry("Density", "1000", Patterns::Double(0), "Density (kg/m^3), > 0.");
    MaterialRegistry<dim>::instance().declare_all(prm);
    prm.enter_subsection("Fracture");
    declare_fracture_parameters(prm);
    FractureModelRegistry<dim>::instance().declare_all(prm);
    prm.leave_subsection();
    prm.leave_subsection();
  }

  for (unsigned int b = 0; b < counts.bodies; ++b)
  {
    prm.enter_subsection(subsection_name("Body", b));
    prm.declare_entry("Material", "1", Patterns::Integer(1),
                      "Number N of the 'Material N' the body is made of.");
    prm.declare_entry(
        "Shape", dim == 2 ? "rectangle(0, 0, 1, 1)" : "rectangle(0, 0, 0, 1, 1, 1)",
        Patterns::Anything(),
        "Region the body fills: " + GeometryRegistry<dim>::instance().documentation());
    prm.declare_entry("Holes", "", Patterns::Anything(),
                      "Regions removed from the shape (notches, holes), separated by "
                      "';', in the same form as 'Shape'.");
    prm.declare_entry("Particle placement", "gauss", Patterns::Selection("gauss|uniform"),
                      "'gauss': particles at the Gauss points of each cell (the paper's "
                      "choice); 'uniform': at the centres of equal sub-cells, so that "
                      "particle boxes tile the body (what uGIMP assumes).");
    prm.declare_entry("Particles per cell direction", "2", Patterns::Integer(1, 8),
                      "Particles at the Gauss points of each background cell, this "
                      "many per direction.");
    prm.enter_subsection("Initial velocity");
    Functions::ParsedFunction<dim>::declare_parameters(prm, dim);
    prm.leave_subsection();
    prm.leave_subsection();
  }

  prm.enter_subsection("Boundary conditions");
  for (unsigned int c = 0; c < counts.constraints; ++c)
  {
    prm.enter_subsection(subsection_name("Constraint", c));
    NodeConstraint<dim>::declare_parameters(prm);
    prm.leave_subsection();
  }
  prm.leave_subsection();

  prm.enter_subsection("Output");
  prm.declare_entry("Directory", "output", Patterns::Anything(),
                    "Directory for VTU/PVD files, history.csv and summary.json.");
  prm.declare_entry("Output interval", "0", Patterns::Double(0),
                    "Simulated time between output rows and files (s); 0: 20 per run.");
  prm.declare_entry("Write particle files", "true", Patterns::Bool(),
                    "Write particle VTU files (history.csv and summary.json always).");
  prm.declare_entry("Write grid files", "false", Patterns::Bool(),
                    "Also write the background grid with nodal velocity and mass.");
  prm.declare_entry(
      "Peak force set", "", Patterns::Anything(),
      "Name of a constrained node set and a component, 'top:y': summary.json "
      "then reports peak_force (largest reaction, checked every step) and "
      "displacement_at_peak (the set's imposed displacement then).");
  prm.declare_entry("Verbosity", "1", Patterns::Integer(0, 2),
                    "0: errors only; 1: progress and timing; 2: more.");
  for (unsigned int p = 0; p < counts.probes; ++p)
  {
    prm.enter_subsection(subsection_name("Probe", p));
    prm.declare_entry("Name", "probe", Patterns::Anything(),
                      "history.csv reports probe_<name>_sxx, ... .");
    prm.declare_entry("Point", dim == 2 ? "0, 0" : "0, 0, 0", Patterns::Anything(),
                      "Centre of the probe (m).");
    prm.declare_entry("Radius", "0.01", Patterns::Double(0),
                      "Particles within this distance are averaged (m), > 0.");
    prm.leave_subsection();
  }
  prm.leave_subsection();

  prm.enter_subsection("Checkpoint");
  prm.declare_entry(
      "Every steps", "0", Patterns::Integer(0),
      "Write output/checkpoint.bin every this many steps (0: never); the "
      "previous one is kept as checkpoint.bin.prev. --resume DIR continues.");
  prm.declare_entry("Every seconds", "0", Patterns::Double(0),
                    "Also write one when this much wall time has passed since the last "
                    "(0: never).");
  prm.leave_subsection();

  prm.enter_subsection("Verification");
  prm.declare_entry("Compare with exact solution", "false", Patterns::Bool(),
                    "Report error_displacement_l2 and error_velocity_l2 against the "
                    "exact fields below, functions of the reference position and t.");
  for (const char *s : {"Exact displacement", "Exact velocity"})
  {
    prm.enter_subsection(s);
    Functions::ParsedFunction<dim>::declare_parameters(prm, dim);
    prm.leave_subsection();
  }
  prm.declare_entry("Compare stress", "false", Patterns::Bool(),
                    "Also report error_stress_l2 against 'Exact stress' (with 'Compare "
                    "with exact solution').");
  prm.enter_subsection("Exact stress");
  Functions::ParsedFunction<dim>::declare_parameters(prm, dim * (dim + 1) / 2);
  prm.leave_subsection();
  prm.leave_subsection();
}

// ------------------------------------------------------------------ setup

template <int dim>
Simulation<dim>::Simulation(ParameterHandler &prm, const ParameterCounts &counts,
                            std::ostream &console)
    : console_stream(console), pcout(console, false)
{
  prm.enter_subsection("Output");
  verbosity                    = prm.get_integer("Verbosity");
  output_directory             = prm.get("Directory");
  output_interval              = prm.get_double("Output interval");
  write_particles              = prm.get_bool("Write particle files");
  const bool grid_files        = prm.get_bool("Write grid files");
  const std::string peak_entry = input::trim(prm.get("Peak force set"));
  prm.leave_subsection();
  pcout.set_condition(verbosity > 0);
  AssertThrow(!input::trim(output_directory).empty(),
              ExcBadInput("Output/Directory", "must not be empty"));

  prm.enter_subsection("Problem");
  thickness = dim == 2 ? prm.get_double("Thickness") : 1.0;
  input::require_range(thickness, 0, 1e300, true, "Problem/Thickness");
  MaterialContext material_context;
  material_context.dim   = dim;
  material_context.plane = prm.get("Plane assumption") == "plane stress"
                               ? PlaneAssumption::plane_stress
                               : PlaneAssumption::plane_strain;
  {
    const auto g = input::parse_doubles(prm.get("Body force"), "Problem/Body force");
    AssertThrow(g.size() >= dim,
                ExcBadInput("Problem/Body force",
                            "needs at least " + std::to_string(dim) + " components"));
    for (unsigned int d = 0; d < dim; ++d)
      body_force[d] = g[d];
  }
  prm.leave_subsection();

  background.parse_parameters(prm);
  cracks.parse_parameters(prm);

  for (unsigned int m = 0; m < counts.materials; ++m)
  {
    const std::string section = subsection_name("Material", m);
    prm.enter_subsection(section);
    material_context.density = prm.get_double("Density");
    material_context.section = section + "/" + prm.get("Model");
    input::require_range(material_context.density, 0, 1e300, true, section + "/Density");
    materials.push_back(MaterialRegistry<dim>::instance().create(prm.get("Model"), prm,
                                                                 material_context));
    prm.enter_subsection("Fracture");
    const std::string fracture_model = prm.get("Model");
    if (fracture_model != "none")
    {
      FractureContext fc;
      fc.grid_spacing = background.min_spacing();
      fc.thickness    = thickness;
      fc.dim          = dim;
      fc.p_wave_modulus =
          material_context.density * std::pow(materials.back()->wave_speed(), 2);
      fc.section = section + "/Fracture";
      fracture_models.push_back(
          FractureModelRegistry<dim>::instance().create(fracture_model, prm, fc));
      fracture_active = true;
    }
    else
      fracture_models.emplace_back();
    prm.leave_subsection();
    prm.leave_subsection();
  }

  prm.enter_subsection("Time");
  end_time = prm.get_double("End time");
  input::require_range(end_time, 0, 1e300, true, "Time/End time");
  newmark.gamma    = prm.get_double("Newmark gamma");
  mass_corrections = prm.get_integer("Mass matrix corrections");
  prm.leave_subsection();
  setup_time_step(prm);

  setup_particles(prm, counts);

  prm.enter_subsection("Shape functions");
  ShapeFunctionContext<dim> sf_context;
  sf_context.grid      = &background;
  sf_context.thickness = thickness;
  shape_function =
      ShapeFunctionRegistry<dim>::instance().create(prm.get("Type"), prm, sf_context);
  prm.leave_subsection();
  if (!cracks.empty())
  {
    crack_reach = shape_function->support_radius(background);
    cracks.assign_fields(background, crack_reach);
  }

  prm.enter_subsection("Boundary conditions");
  for (unsigned int c = 0; c < counts.constraints; ++c)
  {
    const std::string section = subsection_name("Constraint", c);
    prm.enter_subsection(section);
    constraints.push_back(std::make_unique<NodeConstraint<dim>>());
    constraints.back()->parse_parameters(prm, background,
                                         "Boundary conditions/" + section);
    prm.leave_subsection();
    for (unsigned int o = 0; o + 1 < constraints.size(); ++o)
      AssertThrow(constraints[o]->name() != constraints.back()->name(),
                  ExcBadInput("Boundary conditions/" + section + "/Name",
                              "'" + constraints.back()->name() + "' is used twice"));
  }
  prm.leave_subsection();

  if (!peak_entry.empty())
  {
    const auto colon       = peak_entry.find(':');
    const std::string name = input::trim(peak_entry.substr(0, colon));
    const std::string comp =
        colon == std::string::npos ? "" : input::trim(peak_entry.substr(colon + 1));
    for (unsigned int c = 0; c < constraints.size(); ++c)
      if (constraints[c]->name() == name)
        peak_constraint = c;
    AssertThrow(peak_constraint < constraints.size(),
                ExcBadInput("Output/Peak force set",
                            "no constrained node set is named '" + name + "'"));
    AssertThrow(comp.size() == 1 &&
                    std::string("xyz").substr(0, dim).find(comp) != std::string::npos,
                ExcBadInput("Output/Peak force set",
                            "give 'name:x', 'name:y'" +
                                std::string(dim == 3 ? " or 'name:z'" : "")));
    peak_component = std::string("xyz").find(comp);
  }

  prm.enter_subsection("Output");
  for (unsigned int p = 0; p < counts.probes; ++p)
  {
    const std::string section = subsection_name("Probe", p);
    prm.enter_subsection(section);
    Probe<dim> probe;
    probe.name = input::trim(prm.get("Name"));
    probe.point =
        input::parse_point<dim>(prm.get("Point"), "Output/" + section + "/Point");
    probe.radius = prm.get_double("Radius");
    input::require_range(probe.radius, 0, 1e300, true, "Output/" + section + "/Radius");
    probes.push_back(probe);
    prm.leave_subsection();
  }
  prm.leave_subsection();

  prm.enter_subsection("Checkpoint");
  checkpoint_every_steps   = prm.get_integer("Every steps");
  checkpoint_every_seconds = prm.get_double("Every seconds");
  prm.leave_subsection();

  prm.enter_subsection("Verification");
  compare_exact = prm.get_bool("Compare with exact solution");
  if (compare_exact)
  {
    exact_displacement = std::make_unique<Functions::ParsedFunction<dim>>(dim);
    exact_velocity     = std::make_unique<Functions::ParsedFunction<dim>>(dim);
    parse_function(prm, "Exact displacement", *exact_displacement,
                   "Verification/Exact displacement");
    parse_function(prm, "Exact velocity", *exact_velocity, "Verification/Exact velocity");
    if (prm.get_bool("Compare stress"))
    {
      exact_stress =
          std::make_unique<Functions::ParsedFunction<dim>>(dim * (dim + 1) / 2);
      parse_function(prm, "Exact stress", *exact_stress, "Verification/Exact stress");
    }
  }
  prm.leave_subsection();

  if (output_interval <= 0)
    output_interval = end_time / 20;
  output         = std::make_unique<ParticleOutput<dim>>(output_directory, grid_files);
  n_threads_used = MultithreadInfo::n_threads();
}

template <int dim>
void Simulation<dim>::setup_time_step(ParameterHandler &prm)
{
  prm.enter_subsection("Time");
  const double cfl      = prm.get_double("CFL");
  const double fixed_dt = prm.get_double("Time step");
  const double max_cfl  = prm.get_double("Maximum CFL");
  prm.leave_subsection();
  double c_max = 0;
  for (const auto &m : materials)
    c_max = std::max(c_max, m->wave_speed());
  const double dt_wave = background.min_spacing() / c_max;
  if (fixed_dt > 0)
  {
    std::ostringstream msg;
    msg << "dt = " << fixed_dt << " s exceeds the stability limit Maximum CFL * h_min / "
        << "c_P = " << max_cfl * dt_wave << " s (h_min = " << background.min_spacing()
        << " m, c_P = " << c_max << " m/s)";
    AssertThrow(fixed_dt <= max_cfl * dt_wave * (1 + 1e-12),
                ExcBadInput("Time/Time step", msg.str()));
    dt = fixed_dt;
  }
  else
  {
    input::require_range(cfl, 0, max_cfl, false, "Time/CFL");
    AssertThrow(cfl > 0, ExcBadInput("Time/CFL", "must be positive"));
    dt = cfl * dt_wave;
  }
  // Land exactly on the end time.
  n_steps = static_cast<unsigned int>(std::ceil(end_time / dt - 1e-9));
  AssertThrow(n_steps < 2e9, ExcBadInput("Time/End time", "needs more than 2e9 steps"));
  dt = end_time / n_steps;
}

template <int dim>
void Simulation<dim>::setup_particles(ParameterHandler &prm,
                                      const ParameterCounts &counts)
{
  const auto &geometries = GeometryRegistry<dim>::instance();
  const double tol =
      1e-9 * (background.upper_corner() - background.lower_corner()).norm();
  for (unsigned int b = 0; b < counts.bodies; ++b)
  {
    const std::string section = subsection_name("Body", b);
    prm.enter_subsection(section);
    const unsigned int material = prm.get_integer("Material") - 1;
    AssertThrow(material < materials.size(),
                ExcBadInput(section + "/Material",
                            "must be between 1 and Problem/Number of materials = " +
                                std::to_string(materials.size())));
    const auto shape = geometries.create(prm.get("Shape"), section + "/Shape");
    std::vector<std::unique_ptr<Geometry<dim>>> holes;
    for (const auto &h : input::split(prm.get("Holes"), ';'))
      holes.push_back(geometries.create(h, section + "/Holes"));
    const unsigned int n_per_dir = prm.get_integer("Particles per cell direction");
    particle_spacing = std::min(particle_spacing, background.min_spacing() / n_per_dir);
    const std::string placement = prm.get("Particle placement");
    Functions::ParsedFunction<dim> velocity(dim);
    parse_function(prm, "Initial velocity", velocity, section + "/Initial velocity");
    prm.leave_subsection();

    // A neighbourhood narrower than the particle spacing holds only the particle
    // itself: the fracture criterion would then not average anything.
    if (fracture_models[material])
    {
      double h_max = 0;
      for (unsigned int d = 0; d < dim; ++d)
        for (unsigned int i = 0; i + 1 < background.coordinates(d).size(); ++i)
          h_max = std::max(h_max, background.spacing(d, i));
      const double spacing = h_max / n_per_dir;
      AssertThrow(
          fracture_models[material]->epsilon() >= spacing,
          ExcBadInput(subsection_name("Material", material) + "/Fracture/Epsilon factor",
                      "the neighbourhood radius C_eps h = " +
                          std::to_string(fracture_models[material]->epsilon()) +
                          " is smaller than the particle spacing " +
                          std::to_string(spacing) + " of " + section +
                          "; raise it to at least " +
                          std::to_string(spacing / background.min_spacing())));
    }

    // The body must lie inside the grid, or part of it would silently vanish.
    const auto box = shape->bounding_box().get_boundary_points();
    for (unsigned int d = 0; d < dim; ++d)
      if (box.first[d] > -1e299)
        AssertThrow(box.first[d] >= background.lower_corner()[d] - tol &&
                        box.second[d] <= background.upper_corner()[d] + tol,
                    ExcBadInput(section + "/Shape",
                                std::string("the body reaches outside the background "
                                            "grid along ") +
                                    axis[d]));

    // Gauss points of the background cells that overlap the body's box.
    std::array<unsigned int, dim> lo, hi;
    for (unsigned int d = 0; d < dim; ++d)
    {
      const double a = std::max(box.first[d], background.coordinates(d).front());
      const double z = std::min(box.second[d], background.coordinates(d).back());
      background.locate(a, d, lo[d]);
      background.locate(z, d, hi[d]);
    }
    const bool uniform_placement = placement == "uniform";
    const QGauss<1> gauss_rule(n_per_dir);
    const QIterated<1> uniform_rule(QMidpoint<1>(), n_per_dir);
    const Quadrature<1> &gauss        = uniform_placement
                                            ? static_cast<const Quadrature<1> &>(uniform_rule)
                                            : static_cast<const Quadrature<1> &>(gauss_rule);
    const double rho                  = materials[material]->density();
    const std::size_t before          = store.size();
    std::array<unsigned int, dim> ijk = lo;
    while (true)
    {
      std::array<unsigned int, dim> q{};
      while (true)
      {
        Point<dim> x;
        double volume = dim == 2 ? thickness : 1.0;
        for (unsigned int d = 0; d < dim; ++d)
        {
          const double h = background.spacing(d, ijk[d]);
          x[d]           = background.coordinates(d)[ijk[d]] + h * gauss.point(q[d])[0];
          volume *= h * gauss.weight(q[d]);
        }
        bool keep = shape->inside(x);
        for (const auto &h : holes)
          keep = keep && !h->inside(x);
        if (keep)
        {
          const std::size_t p = store.add(x, rho * volume, volume, material, b);
          for (unsigned int d = 0; d < dim; ++d)
            store.velocity[p][d] = velocity.value(x, d);
        }
        unsigned int d = 0;
        while (d < dim && ++q[d] == n_per_dir)
          q[d++] = 0;
        if (d == dim)
          break;
      }
      unsigned int d = 0;
      while (d < dim && ++ijk[d] > hi[d])
        ijk[d] = lo[d], ++d;
      if (d == dim)
        break;
    }
    AssertThrow(store.size() > before,
                ExcBadInput(section + "/Shape", "the body holds no particle: it is "
                                                "smaller than a cell or fully cut away"));
  }
  for (std::size_t p = 0; p < store.size(); ++p)
    store.id[p] = static_cast<std::uint32_t>(p);
}

// ------------------------------------------------------------------ one step

template <int dim>
void Simulation<dim>::abort_run(const std::size_t p, const std::string &why) const
{
  AssertThrow(false, ExcRunAborted(step_count, t, store.id[p],
                                   point_to_string(store.position[p]), why));
}

template <int dim>
void Simulation<dim>::locate_and_sort()
{
  const std::size_t n = store.size();
  // The first particle outside the grid (lowest index, so the report is reproducible).
  std::atomic<std::size_t> lost{n};
  parallel::for_range(n,
                      [&](const std::size_t b, const std::size_t e)
                      {
                        std::array<unsigned int, dim> ijk;
                        for (std::size_t p = b; p < e; ++p)
                          if (background.locate(store.position[p], ijk))
                            store.cell[p] = background.cell_index(ijk);
                          else
                          {
                            std::size_t cur = lost.load();
                            while (p < cur && !lost.compare_exchange_weak(cur, p))
                              ;
                          }
                      });
  if (lost.load() < n)
    abort_run(lost.load(), "the particle left the background grid (enlarge the grid, or "
                           "the run is unstable: lower the CFL number)");
  store.sort_by_cell(background.n_cells());
}

template <int dim>
std::pair<unsigned int, unsigned int>
Simulation<dim>::support_reach(const std::size_t begin, const std::size_t end) const
{
  // How many cell layers the supports of [begin, end) reach below and above their
  // particles' layers.
  unsigned int below = 0, above = 0;
  for (std::size_t p = begin; p < end; ++p)
  {
    const unsigned int layer = background.cell_layer(store.cell[p]);
    const unsigned int *row  = &conn.nodes[p * conn.stride];
    const unsigned int lo    = background.node_layer(row[0]);
    const unsigned int hi    = background.node_layer(row[conn.n_nodes[p] - 1]);
    below                    = std::max(below, layer > lo ? layer - lo : 0u);
    above                    = std::max(above, hi > layer ? hi - layer : 0u);
  }
  return {below, above};
}

template <int dim>
template <class F>
void Simulation<dim>::scatter(const F &f)
{
  scatter_chunks(
      [&](const std::size_t b, const std::size_t e)
      {
        for (std::size_t p = b; p < e; ++p)
          f(p);
      });
}

template <int dim>
template <class F>
void Simulation<dim>::scatter_chunks(const F &f)
{
  // Slabs of slab_below + slab_above cell layers: every scattering particle's support
  // lies within slab_below layers below and slab_above above its own, so slabs of one
  // colour touch disjoint nodes and run concurrently, each in particle order: sums do
  // not depend on threads.
  const auto &offsets         = store.cell_offsets();
  const unsigned int cpl      = background.cells_per_layer();
  const unsigned int n_layers = background.n_cells_in(dim - 1);
  const unsigned int w        = std::max(1u, slab_below + slab_above);
  const unsigned int n_slabs  = (n_layers + w - 1) / w;
  auto run_slab               = [&](const unsigned int s)
  {
    const std::size_t b = offsets[s * w * cpl];
    const std::size_t e = offsets[std::min((s + 1) * w, n_layers) * cpl];
    for (std::size_t c = b; c < e; c += scatter_chunk)
      f(c, std::min(e, c + scatter_chunk));
  };
  for (unsigned int colour = 0; colour < 2; ++colour)
  {
    const unsigned int n_this = (n_slabs + 1 - colour) / 2;
    if (n_threads_used == 1 || n_this < 2)
      for (unsigned int i = 0; i < n_this; ++i)
        run_slab(colour + 2 * i);
    else
      dealii::parallel::apply_to_subranges(
          0u, n_this,
          [&](const unsigned int i0, const unsigned int i1)
          {
            for (unsigned int i = i0; i < i1; ++i)
              run_slab(colour + 2 * i);
          },
          1);
  }
}

template <int dim>
void Simulation<dim>::step()
{
  const std::size_t n_p = store.size();
  const double t_half = t + 0.5 * dt, t_new = t + dt;

  // A crack that grew with last step's failures separates the field along its new
  // part from this step on.
  if (fracture_active && cracks.grow(store, particle_spacing))
    cracks.assign_fields(background, crack_reach);
  locate_and_sort();

  // Particle to grid: mass, momentum and mass-weighted acceleration.
  const auto particle_to_grid = [&](const std::size_t b, const std::size_t e)
  {
    for (std::size_t p = b; p < e; ++p)
    {
      const std::size_t o     = p * conn.stride;
      const double m          = store.mass[p];
      const Tensor<1, dim> mv = m * store.velocity[p], ma = m * store.acceleration[p];
      for (unsigned int k = 0; k < conn.n_nodes[p]; ++k)
      {
        const unsigned int I = conn.nodes[o + k];
        const double N       = conn.N[o + k];
        nodal_mass[I] += N * m;
        nodal_momentum[I] += N * mv;
        nodal_mass_acceleration[I] += N * ma;
      }
    }
  };
  // Each chunk gets its shape functions and scatters them while they are in cache,
  // in slabs sized by the reach of the supports so far. A chunk whose supports reach
  // further does not scatter (so no two threads can meet on a node); the reach is
  // then widened and the whole transfer repeated, which happens on the first step
  // and where supports grow. The order depends on the particles only, not on the
  // threads.
  clear_nodal_arrays();
  conn.resize(n_p, shape_function->max_nodes_per_particle());
  if (!cracks.empty())
    touches_crack.resize(n_p);
  const unsigned int below = slab_below, above = slab_above;
  std::atomic<unsigned int> reach_below{below}, reach_above{above};
  const auto raise = [](std::atomic<unsigned int> &m, const unsigned int v)
  {
    unsigned int seen = m.load();
    while (v > seen && !m.compare_exchange_weak(seen, v))
    {
    }
  };
  scatter_chunks(
      [&](const std::size_t b, const std::size_t e)
      {
        shape_function->compute(store, b, e, conn);
        const auto [chunk_below, chunk_above] = support_reach(b, e);
        cracks.separate(store, background, conn, b, e, touches_crack.data());
        if (chunk_below <= below && chunk_above <= above)
          particle_to_grid(b, e);
        raise(reach_below, chunk_below);
        raise(reach_above, chunk_above);
      });
  if (reach_below.load() > below || reach_above.load() > above)
  {
    slab_below = reach_below.load(), slab_above = reach_above.load();
    collect_active_nodes();
    clear_nodal_arrays();
    scatter_chunks(particle_to_grid);
  }

  collect_active_nodes();

  // Displacement predictor on the grid, then the essential conditions on it.
  for_active_nodes(
      [&](const unsigned int I)
      {
        nodal_rate[I] = nodal_mass[I] > mass_tolerance
                            ? newmark.displacement_rate(
                                  nodal_momentum[I] / nodal_mass[I],
                                  nodal_mass_acceleration[I] / nodal_mass[I], dt)
                            : Tensor<1, dim>();
      });
  auto constrain_rate = [&](std::vector<Tensor<1, dim>> &x)
  {
    for (auto &c : constraints)
      for (unsigned int i = 0; i < c->nodes().size(); ++i)
      {
        const Tensor<1, dim> v = c->velocity(i, t_half);
        const unsigned int I   = c->nodes()[i];
        const unsigned int J   = cracks.second_field(I);
        for (unsigned int d = 0; d < dim; ++d)
          if (c->constrains(d))
          {
            x[I][d] = v[d];
            if (J != numbers::invalid_unsigned_int)
              x[background.n_nodes() + J][d] = v[d];
          }
      }
  };
  crack_face_contact(nodal_rate, nullptr);
  constrain_rate(nodal_rate);
  if (mass_corrections > 0)
  {
    for_active_nodes(
        [&](const unsigned int I)
        { nodal_rhs[I] = nodal_momentum[I] + (0.5 * dt) * nodal_mass_acceleration[I]; });
    correct_towards_consistent_mass(nodal_rate, nodal_rhs, constrain_rate);
  }

  // Strain increment, density and the particle displacement increment.
  particle_increment.resize(n_p);
  const auto strain_increments = [&](const std::size_t b, const std::size_t e)
  {
    for (std::size_t p = b; p < e; ++p)
    {
      const std::size_t o = p * conn.stride;
      Tensor<2, dim> grad_v;
      Tensor<1, dim> v;
      for (unsigned int k = 0; k < conn.n_nodes[p]; ++k)
      {
        const Tensor<1, dim> &w = nodal_rate[conn.nodes[o + k]];
        grad_v += outer_product(w, conn.grad_N[o + k]);
        v += conn.N[o + k] * w;
      }
      const SymmetricTensor<2, dim> de = dt * symmetrize(grad_v);
      store.strain_increment[p]        = de;
      store.strain[p] += de;
      store.density[p] /= (1 + trace(de));
      store.volume[p]       = store.mass[p] / store.density[p];
      particle_increment[p] = dt * v;
    }
  };
  // Constitutive update, one call per material and block.
  const auto stresses = [&](const std::size_t b, const std::size_t e)
  {
    for (unsigned int m = 0; m < materials.size(); ++m)
      materials[m]->update_stress(store, b, e, m);
  };
  // Grid forces: internal (damaged stress) and body force.
  const bool gravity = body_force.norm_square() > 0;
  const auto forces  = [&](const std::size_t b, const std::size_t e)
  {
    for (std::size_t p = b; p < e; ++p)
    {
      const std::size_t o = p * conn.stride;
      // A full tensor: the symmetric one's element access costs more per node.
      const Tensor<2, dim> s =
          (store.failed[p] ? 0.0 : (1 - store.damage[p]) * store.initial_volume[p]) *
          store.stress[p];
      const unsigned int n = conn.n_nodes[p];
      if (gravity)
      {
        const Tensor<1, dim> g = store.mass[p] * body_force;
        for (unsigned int k = 0; k < n; ++k)
          nodal_force[conn.nodes[o + k]] += conn.N[o + k] * g - s * conn.grad_N[o + k];
      }
      else
        for (unsigned int k = 0; k < n; ++k)
          nodal_force[conn.nodes[o + k]] -= s * conn.grad_N[o + k];
    }
  };
  if (fracture_active)
  {
    // The fracture update couples particles through their neighbourhoods: all
    // stresses first.
    parallel::for_range(n_p, strain_increments);
    parallel::for_range(n_p, stresses);
    update_fracture();
    scatter_chunks(forces);
  }
  else
    // Without it each particle's strain, stress and force follow one another,
    // chunk by chunk while its connectivity is in cache: the same arithmetic in
    // the same order, one pass over the connectivity fewer.
    scatter_chunks(
        [&](const std::size_t b, const std::size_t e)
        {
          strain_increments(b, e);
          stresses(b, e);
          forces(b, e);
        });

  // Accelerations, the constraints' accelerations and their reactions.
  for_active_nodes(
      [&](const unsigned int I)
      {
        nodal_acceleration[I] = nodal_mass[I] > mass_tolerance
                                    ? nodal_force[I] / nodal_mass[I]
                                    : Tensor<1, dim>();
      });
  auto constrain_acceleration = [&](std::vector<Tensor<1, dim>> &x)
  {
    for (auto &c : constraints)
      for (unsigned int i = 0; i < c->nodes().size(); ++i)
      {
        const Tensor<1, dim> dv = c->velocity(i, t_new) - c->velocity(i, t);
        const unsigned int I    = c->nodes()[i];
        const unsigned int J    = cracks.second_field(I);
        for (unsigned int d = 0; d < dim; ++d)
          if (c->constrains(d))
          {
            x[I][d] = dv[d] / dt;
            if (J != numbers::invalid_unsigned_int)
              x[background.n_nodes() + J][d] = dv[d] / dt;
          }
      }
  };
  crack_face_contact(nodal_acceleration, &nodal_rate);
  constrain_acceleration(nodal_acceleration);
  // The reaction is what the constraint adds to the force: (M a - f) on its nodes.
  const std::vector<Tensor<1, dim>> *mass_times_acceleration = nullptr;
  if (mass_corrections > 0)
  {
    correct_towards_consistent_mass(nodal_acceleration, nodal_force,
                                    constrain_acceleration);
    if (!constraints.empty())
    {
      apply_consistent_mass(nodal_acceleration, nodal_rhs);
      mass_times_acceleration = &nodal_rhs;
    }
  }
  // Work of the reactions over the step: the mean of the old and new reaction times
  // the imposed displacement increment (exact for the central-difference scheme).
  double work = 0;
  for (auto &c : constraints)
  {
    c->reaction = Tensor<1, dim>();
    Tensor<1, dim> mean_rate;
    for (unsigned int i = 0; i < c->nodes().size(); ++i)
    {
      const unsigned int I = c->nodes()[i];
      const unsigned int J = cracks.second_field(I);
      // A constrained node's second field (a crack reaching the set) is constrained
      // with it; its reaction adds to the node's.
      const auto reaction_at = [&](const unsigned int K, const unsigned int d)
      {
        const double ma = mass_times_acceleration
                              ? (*mass_times_acceleration)[K][d]
                              : nodal_mass[K] * nodal_acceleration[K][d];
        return ma - nodal_force[K][d];
      };
      for (unsigned int d = 0; d < dim; ++d)
        if (c->constrains(d))
        {
          const double r =
              reaction_at(I, d) + (J != numbers::invalid_unsigned_int
                                       ? reaction_at(background.n_nodes() + J, d)
                                       : 0.0);
          c->reaction[d] += r;
          work += 0.5 * (c->node_reaction[i][d] + r) * dt * nodal_rate[I][d];
          c->node_reaction[i][d] = r;
          mean_rate[d] += nodal_rate[I][d];
        }
    }
    c->displacement += (dt / c->nodes().size()) * mean_rate;
  }
  if (peak_constraint < constraints.size() &&
      constraints[peak_constraint]->reaction[peak_component] > peak_force)
  {
    peak_force           = constraints[peak_constraint]->reaction[peak_component];
    displacement_at_peak = constraints[peak_constraint]->displacement[peak_component];
  }

  // Grid to particle: Newmark corrector for velocity, predictor for position.
  std::atomic<std::size_t> bad{n_p};
  const double max_move = 0.5 * background.min_spacing();
  // A constant body force does work m b . dx over the step's displacement exactly.
  const double body_work = parallel::deterministic_sum<double>(
      n_p,
      [&](const std::size_t b, const std::size_t e)
      {
        double pw = 0;
        for (std::size_t p = b; p < e; ++p)
        {
          const std::size_t o = p * conn.stride;
          Tensor<1, dim> a;
          for (unsigned int k = 0; k < conn.n_nodes[p]; ++k)
            a += conn.N[o + k] * nodal_acceleration[conn.nodes[o + k]];
          store.velocity[p] =
              newmark.corrected_velocity(store.velocity[p], store.acceleration[p], a, dt);
          store.acceleration[p] = a;
          store.position[p] += particle_increment[p];
          pw += store.mass[p] * (body_force * particle_increment[p]);
          const double move = particle_increment[p].norm();
          if (!(move < max_move) || !std::isfinite(store.velocity[p].norm_square()) ||
              !(store.density[p] > 0))
          {
            std::size_t cur = bad.load();
            while (p < cur && !bad.compare_exchange_weak(cur, p))
              ;
          }
        }
        return pw;
      });
  external_work += work + body_work;
  t = t_new;
  ++step_count;

  if (bad.load() < n_p)
  {
    const std::size_t p = bad.load();
    std::string why;
    if (!std::isfinite(store.velocity[p].norm_square()))
      why = "non-finite velocity (the run is unstable: lower the CFL number)";
    else if (!(store.density[p] > 0))
      why = "non-positive density (the material is inverted: the run is unstable, lower "
            "the CFL number, or the deformation is too large for a small-strain model)";
    else
      why = "the particle moved more than half a cell in one step (the run is "
            "unstable or the time step too large: lower the CFL number)";
    abort_run(p, why);
  }
}

template <int dim>
void Simulation<dim>::clear_nodal_arrays()
{
  const unsigned int n_n   = background.n_nodes() + cracks.n_extra_nodes();
  const auto vector_fields = {&nodal_momentum, &nodal_mass_acceleration, &nodal_rate,
                              &nodal_force,    &nodal_acceleration,      &nodal_rhs,
                              &nodal_scratch};
  if (nodal_mass.size() != n_n)
  {
    nodal_mass.assign(n_n, 0.0);
    for (auto *v : vector_fields)
      v->assign(n_n, Tensor<1, dim>());
    active_nodes.clear();
    return;
  }
  auto clear = [&](const unsigned int I)
  {
    nodal_mass[I] = 0;
    for (auto *v : vector_fields)
      (*v)[I] = Tensor<1, dim>();
  };
  for_active_nodes(clear);
  // Constraints write their values on nodes (and their crack fields) that may hold no
  // mass.
  for (const auto &c : constraints)
    for (const unsigned int I : c->nodes())
    {
      clear(I);
      if (cracks.second_field(I) != numbers::invalid_unsigned_int)
        clear(background.n_nodes() + cracks.second_field(I));
    }
}

template <int dim>
void Simulation<dim>::collect_active_nodes()
{
  // A scan of the mass array: a few hundred kilobytes even for large grids, far less
  // than clearing and updating every nodal array over the whole grid.
  const unsigned int n_n = nodal_mass.size();
  active_nodes.clear();
  for (unsigned int I = 0; I < n_n; ++I)
    if (nodal_mass[I] != 0)
      active_nodes.push_back(I);
}

template <int dim>
void Simulation<dim>::crack_face_contact(std::vector<Tensor<1, dim>> &x,
                                         const std::vector<Tensor<1, dim>> *rate)
{
  // Frictionless contact of the two fields of a node where the faces have closed (the
  // fields' mean displacements no longer open the crack) and approach each other along
  // its normal: both take the mass-weighted mean normal velocity, which conserves
  // momentum. Called on the displacement rate (rate == nullptr), then on the
  // acceleration with the trial end-of-step velocity rate + gamma dt a, so that faces
  // pulled apart by their forces separate even when their rates were made equal.
  if (!cracks.face_contact() || cracks.n_extra_nodes() == 0)
    return;
  const unsigned int n_grid = background.n_nodes();
  if (!rate)
  {
    // Mass-weighted particle displacements of each field of the crack nodes (the
    // only entries written and read).
    nodal_displacement.resize(nodal_mass.size());
    for (unsigned int J = 0; J < cracks.n_extra_nodes(); ++J)
      nodal_displacement[cracks.primary_of(J)] = nodal_displacement[n_grid + J] =
          Tensor<1, dim>();
    scatter(
        [&](const std::size_t p)
        {
          if (!touches_crack[p])
            return;
          const std::size_t o = p * conn.stride;
          const Tensor<1, dim> u =
              store.mass[p] * (store.position[p] - store.reference_position[p]);
          for (unsigned int k = 0; k < conn.n_nodes[p]; ++k)
          {
            const unsigned int K = conn.nodes[o + k];
            if (K >= n_grid || cracks.second_field(K) != numbers::invalid_unsigned_int)
              nodal_displacement[K] += conn.N[o + k] * u;
          }
        });
    faces_closed.assign(cracks.n_extra_nodes(), 0);
    for (unsigned int J = 0; J < cracks.n_extra_nodes(); ++J)
    {
      const unsigned int I = cracks.primary_of(J), K = n_grid + J;
      const double mI = nodal_mass[I], mK = nodal_mass[K];
      faces_closed[J] = mI > mass_tolerance && mK > mass_tolerance &&
                        (nodal_displacement[I] / mI - nodal_displacement[K] / mK) *
                                cracks.normal_of(J) >=
                            0;
    }
  }
  const double scale = rate ? newmark.gamma * dt : 1.0;
  for (unsigned int J = 0; J < cracks.n_extra_nodes(); ++J)
  {
    if (!faces_closed[J])
      continue;
    const unsigned int I = cracks.primary_of(J), K = n_grid + J;
    const Tensor<1, dim> &n = cracks.normal_of(J);
    const double mI = nodal_mass[I], mK = nodal_mass[K];
    const double vI = rate ? ((*rate)[I] + scale * x[I]) * n : x[I] * n;
    const double vK = rate ? ((*rate)[K] + scale * x[K]) * n : x[K] * n;
    if (!(vI > vK))
      continue;
    const double mean = (mI * vI + mK * vK) / (mI + mK);
    x[I] += ((mean - vI) / scale) * n;
    x[K] += ((mean - vK) / scale) * n;
  }
}

template <int dim>
template <class F>
void Simulation<dim>::for_active_nodes(const F &f) const
{
  parallel::for_range(active_nodes.size(),
                      [&](const std::size_t b, const std::size_t e)
                      {
                        for (std::size_t i = b; i < e; ++i)
                          f(active_nodes[i]);
                      });
}

template <int dim>
void Simulation<dim>::apply_consistent_mass(const std::vector<Tensor<1, dim>> &x,
                                            std::vector<Tensor<1, dim>> &Mx)
{
  // (M_C x)_I = sum_p N_Ip m_p sum_J N_Jp x_J: interpolate, then scatter back.
  const std::size_t n_p = store.size();
  particle_scratch.resize(n_p);
  parallel::for_range(n_p,
                      [&](const std::size_t b, const std::size_t e)
                      {
                        for (std::size_t p = b; p < e; ++p)
                        {
                          const std::size_t o = p * conn.stride;
                          Tensor<1, dim> xp;
                          for (unsigned int k = 0; k < conn.n_nodes[p]; ++k)
                            xp += conn.N[o + k] * x[conn.nodes[o + k]];
                          particle_scratch[p] = store.mass[p] * xp;
                        }
                      });
  for (const unsigned int I : active_nodes)
    Mx[I] = Tensor<1, dim>();
  scatter(
      [&](const std::size_t p)
      {
        const std::size_t o = p * conn.stride;
        for (unsigned int k = 0; k < conn.n_nodes[p]; ++k)
          Mx[conn.nodes[o + k]] += conn.N[o + k] * particle_scratch[p];
      });
}

template <int dim>
template <class Constrain>
void Simulation<dim>::correct_towards_consistent_mass(
    std::vector<Tensor<1, dim>> &x, const std::vector<Tensor<1, dim>> &rhs,
    const Constrain &constrain)
{
  // Jacobi iterations on M_C x = rhs preconditioned by the lumped mass, starting from
  // the lumped solution; constrained components stay at their prescribed values.
  for (unsigned int k = 0; k < mass_corrections; ++k)
  {
    apply_consistent_mass(x, nodal_scratch);
    for_active_nodes(
        [&](const unsigned int I)
        {
          if (nodal_mass[I] > mass_tolerance)
            x[I] += (rhs[I] - nodal_scratch[I]) / nodal_mass[I];
        });
    constrain(x);
  }
}

namespace
{
const char checkpoint_magic[9] = "LMEMPMC3";

template <class T>
void put(std::ostream &out, const T &v)
{
  static_assert(std::is_trivially_copyable_v<T>);
  out.write(reinterpret_cast<const char *>(&v), sizeof(T));
}
template <class T>
void get(std::istream &in, T &v)
{
  static_assert(std::is_trivially_copyable_v<T>);
  in.read(reinterpret_cast<char *>(&v), sizeof(T));
}
template <class T>
void put_vector(std::ostream &out, const std::vector<T> &v)
{
  put(out, std::uint64_t(v.size()));
  out.write(reinterpret_cast<const char *>(v.data()), v.size() * sizeof(T));
}
template <class T>
void get_vector(std::istream &in, std::vector<T> &v)
{
  std::uint64_t n = 0;
  get(in, n);
  v.resize(n);
  in.read(reinterpret_cast<char *>(v.data()), n * sizeof(T));
}
void put_records(std::ostream &out, const std::vector<std::pair<double, std::string>> &r)
{
  put(out, std::uint64_t(r.size()));
  for (const auto &[time, name] : r)
  {
    put(out, time);
    put(out, std::uint64_t(name.size()));
    out.write(name.data(), name.size());
  }
}
void get_records(std::istream &in, std::vector<std::pair<double, std::string>> &r)
{
  std::uint64_t n = 0;
  get(in, n);
  r.resize(n);
  for (auto &[time, name] : r)
  {
    std::uint64_t len = 0;
    get(in, time);
    get(in, len);
    name.resize(len);
    in.read(name.data(), len);
  }
}
} // namespace

template <int dim>
void Simulation<dim>::write_checkpoint()
{
  // Everything a resumed run needs to continue bit for bit: the particles, the driver's
  // accumulators and the output series. Nodal fields are rebuilt every step.
  const std::string file = output_directory + "/checkpoint.bin";
  {
    std::ofstream out(file + ".tmp", std::ios::binary);
    AssertThrow(out, ExcMessage("Cannot write the checkpoint '" + file + ".tmp'"));
    history.flush();
    out.write(checkpoint_magic, 8);
    put(out, std::uint32_t(dim));
    put(out, std::uint64_t(store.size()));
    put(out, dt);
    put(out, std::uint32_t(n_steps));
    put(out, t);
    put(out, std::uint32_t(step_count));
    put(out, std::uint32_t(slab_below));
    put(out, std::uint32_t(slab_above));
    for (const double v :
         {external_work, initial_total_energy, energy_scale, max_energy_drift,
          next_output_time, peak_force, displacement_at_peak, max_error_displacement,
          max_error_velocity, max_error_stress})
      put(out, v);
    put(out,
        std::uint64_t(std::filesystem::file_size(output_directory + "/history.csv")));
    for (const auto &c : constraints)
    {
      put(out, c->reaction);
      put(out, c->displacement);
      put_vector(out, c->node_reaction);
    }
    put_records(out, output->particle_series());
    put_records(out, output->grid_series());
    store.for_each_field([&](auto &field) { put_vector(out, field); });
    put(out, std::uint64_t(cracks.polylines().size()));
    for (const auto &line : cracks.polylines())
      put_vector(out, line);
    AssertThrow(out, ExcMessage("Writing the checkpoint '" + file + ".tmp' failed"));
  }
  if (std::filesystem::exists(file))
    std::filesystem::rename(file, file + ".prev");
  std::filesystem::rename(file + ".tmp", file);
}

template <int dim>
void Simulation<dim>::resume_from(const std::string &directory)
{
  const std::string file = directory + "/checkpoint.bin";
  std::ifstream in(file, std::ios::binary);
  AssertThrow(in, ExcBadInput("--resume", "no checkpoint '" + file + "'"));
  char magic[8];
  in.read(magic, 8);
  AssertThrow(in && std::string(magic, 7) == std::string(checkpoint_magic, 7),
              ExcBadInput("--resume", "'" + file + "' is not an lme-mpm checkpoint"));
  AssertThrow(std::string(magic, 8) == std::string(checkpoint_magic, 8),
              ExcBadInput("--resume", "'" + file +
                                          "' was written by another version of " +
                                          "lme-mpm (format " + std::string(magic + 7, 1) +
                                          ", this one reads " +
                                          std::string(checkpoint_magic + 7, 1) + ")"));
  std::uint32_t file_dim = 0, file_steps = 0, file_step = 0;
  std::uint64_t n = 0;
  double file_dt  = 0;
  get(in, file_dim);
  get(in, n);
  get(in, file_dt);
  get(in, file_steps);
  std::ostringstream mismatch;
  mismatch << "the checkpoint holds a " << file_dim << "D run of " << n
           << " particles with dt = " << file_dt << " s; this parameter file gives "
           << dim << "D, " << store.size() << " particles, dt = " << dt
           << " s: resume with the parameter file (and --set "
           << "values) of the run that wrote it";
  AssertThrow(file_dim == dim && n == store.size() && file_dt == dt,
              ExcBadInput("--resume", mismatch.str()));
  get(in, t);
  get(in, file_step);
  step_count               = file_step;
  std::uint32_t file_below = 0, file_above = 0;
  get(in, file_below);
  get(in, file_above);
  slab_below = file_below, slab_above = file_above;
  for (double *v :
       {&external_work, &initial_total_energy, &energy_scale, &max_energy_drift,
        &next_output_time, &peak_force, &displacement_at_peak, &max_error_displacement,
        &max_error_velocity, &max_error_stress})
    get(in, *v);
  get(in, resumed_history_size);
  for (auto &c : constraints)
  {
    get(in, c->reaction);
    get(in, c->displacement);
    get_vector(in, c->node_reaction);
  }
  typename ParticleOutput<dim>::Records particle_series, grid_series;
  get_records(in, particle_series);
  get_records(in, grid_series);
  store.for_each_field([&](auto &field) { get_vector(in, field); });
  std::uint64_t n_cracks = 0;
  get(in, n_cracks);
  AssertThrow(in && n_cracks == cracks.polylines().size(),
              ExcBadInput("--resume", "the checkpoint holds " + std::to_string(n_cracks) +
                                          " cracks, the parameter file " +
                                          std::to_string(cracks.polylines().size())));
  std::vector<std::vector<Point<dim>>> crack_lines(n_cracks);
  for (auto &line : crack_lines)
    get_vector(in, line);
  AssertThrow(in, ExcBadInput("--resume", "'" + file + "' is truncated"));
  cracks.restore(std::move(crack_lines));
  cracks.assign_fields(background, crack_reach);
  AssertThrow(step_count <= n_steps,
              ExcBadInput("--resume", "the checkpoint is past this run's end time"));
  output_directory = directory;
  output           = std::make_unique<ParticleOutput<dim>>(directory, false);
  output->restore(particle_series, grid_series);
  resumed = true;
}

template <int dim>
std::uint64_t Simulation<dim>::state_checksum()
{
  std::uint64_t hash = 1469598103934665603ull;
  auto bytes         = [&](const void *data, const std::size_t size)
  {
    const auto *c = static_cast<const unsigned char *>(data);
    for (std::size_t i = 0; i < size; ++i)
      hash = (hash ^ c[i]) * 1099511628211ull;
  };
  bytes(&t, sizeof(t));
  store.for_each_field([&](auto &field)
                       { bytes(field.data(), field.size() * sizeof(field[0])); });
  return hash;
}

template <int dim>
SymmetricTensor<2, dim> Simulation<dim>::exact_stress_at(const Point<dim> &X) const
{
  // Components in the order xx, xy, (xz,) yy, (yz, zz).
  SymmetricTensor<2, dim> s;
  unsigned int c = 0;
  for (unsigned int i = 0; i < dim; ++i)
    for (unsigned int j = i; j < dim; ++j)
      s[i][j] = exact_stress->value(X, c++);
  return s;
}

template <int dim>
void Simulation<dim>::update_fracture()
{
  const std::size_t n = store.size();
  double radius       = 0;
  for (const auto &f : fracture_models)
    if (f)
      radius = std::max(radius, f->epsilon());
  neighbours.build(store.position, radius);
  // Snapshot of what neighbours read, so that no update sees another's new state.
  fracture_fields.max_principal_stress.resize(n);
  fracture_fields.energy_density.resize(n);
  parallel::for_range(n,
                      [&](const std::size_t b, const std::size_t e)
                      {
                        for (std::size_t p = b; p < e; ++p)
                        {
                          const bool alive = !store.failed[p];
                          fracture_fields.max_principal_stress[p] =
                              alive ? eigenvalues(store.stress[p])[0] : 0.0;
                          fracture_fields.energy_density[p] =
                              alive ? 0.5 * (1 - store.damage[p]) *
                                          (store.stress[p] * store.strain[p])
                                    : 0.0;
                        }
                      });
  parallel::for_range(n,
                      [&](const std::size_t b, const std::size_t e)
                      {
                        for (unsigned int m = 0; m < fracture_models.size(); ++m)
                          if (fracture_models[m])
                            fracture_models[m]->update(store, neighbours, fracture_fields,
                                                       b, e, m);
                      });
}

// ------------------------------------------------------------------ reporting

template <int dim>
std::map<std::string, double> Simulation<dim>::energies() const
{
  const std::size_t n = store.size();
  const double ke     = parallel::deterministic_sum<double>(
      n,
      [&](const std::size_t b, const std::size_t e)
      {
        double s = 0;
        for (std::size_t p = b; p < e; ++p)
          s += 0.5 * store.mass[p] * store.velocity[p].norm_square();
        return s;
      });
  const double se = parallel::deterministic_sum<double>(
      n,
      [&](const std::size_t b, const std::size_t e)
      {
        double s = 0;
        for (unsigned int m = 0; m < materials.size(); ++m)
          s += materials[m]->strain_energy(store, b, e, m);
        return s;
      });
  const double dissipated =
      parallel::deterministic_sum<double>(n,
                                          [&](const std::size_t b, const std::size_t e)
                                          {
                                            double s = 0;
                                            for (std::size_t p = b; p < e; ++p)
                                              s += store.dissipated[p];
                                            return s;
                                          });
  return {{"kinetic_energy", ke},
          {"strain_energy", se},
          {"dissipated_energy", dissipated},
          {"external_work", external_work},
          {"total_energy", ke + se + dissipated - external_work}};
}

template <int dim>
void Simulation<dim>::write_output_row(const bool final_row)
{
  (void)final_row;
  auto e = energies();
  if (step_count == 0)
    initial_total_energy = e["total_energy"];
  // Relative to the largest energy in play, so a body starting at rest is measured too.
  energy_scale =
      std::max({energy_scale, std::abs(initial_total_energy),
                e["kinetic_energy"] + e["strain_energy"] + e["dissipated_energy"],
                std::abs(e["external_work"])});
  const double drift =
      std::abs(e["total_energy"] - initial_total_energy) / std::max(energy_scale, 1e-300);
  max_energy_drift = std::max(max_energy_drift, drift);

  std::ostringstream row;
  row << std::setprecision(10) << step_count << "," << t << "," << e["kinetic_energy"]
      << "," << e["strain_energy"] << "," << e["dissipated_energy"] << ","
      << e["external_work"] << "," << e["total_energy"];
  for (const auto &c : constraints)
  {
    for (unsigned int d = 0; d < dim; ++d)
      row << "," << c->reaction[d];
    for (unsigned int d = 0; d < dim; ++d)
      row << "," << c->displacement[d];
  }
  for (const auto &probe : probes)
  {
    SymmetricTensor<2, dim> s;
    double w = 0;
    for (std::size_t p = 0; p < store.size(); ++p)
      if (store.position[p].distance(probe.point) <= probe.radius)
        s += store.volume[p] * store.stress[p], w += store.volume[p];
    if (w > 0)
      s /= w;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = i; j < dim; ++j)
        row << "," << s[i][j];
  }
  if (compare_exact)
  {
    exact_displacement->set_time(t);
    exact_velocity->set_time(t);
    double eu = 0, ev = 0;
    for (std::size_t p = 0; p < store.size(); ++p)
    {
      const Point<dim> &X = store.reference_position[p];
      for (unsigned int d = 0; d < dim; ++d)
      {
        const double du = store.position[p][d] - X[d] - exact_displacement->value(X, d);
        const double dv = store.velocity[p][d] - exact_velocity->value(X, d);
        eu += store.initial_volume[p] * du * du;
        ev += store.initial_volume[p] * dv * dv;
      }
    }
    const double err_u     = std::sqrt(eu) / exact_displacement_norm;
    const double err_v     = std::sqrt(ev) / exact_velocity_norm;
    max_error_displacement = std::max(max_error_displacement, err_u);
    max_error_velocity     = std::max(max_error_velocity, err_v);
    row << "," << err_u << "," << err_v;
    if (exact_stress)
    {
      exact_stress->set_time(t);
      double es = 0;
      for (std::size_t p = 0; p < store.size(); ++p)
      {
        const auto e = store.stress[p] - exact_stress_at(store.reference_position[p]);
        es += store.initial_volume[p] * (e * e);
      }
      const double err_s = std::sqrt(es) / exact_stress_norm;
      max_error_stress   = std::max(max_error_stress, err_s);
      row << "," << err_s;
    }
  }
  history << row.str() << "\n" << std::flush;
  results["final_total_energy"]   = e["total_energy"];
  results["final_kinetic_energy"] = e["kinetic_energy"];
  results["final_strain_energy"]  = e["strain_energy"];

  if (write_particles)
    output->write(store, t);
  output->write_grid(background, nodal_mass, nodal_rate, t);
}

// ------------------------------------------------------------------ driver

template <int dim>
std::map<std::string, double> Simulation<dim>::run()
{
  TimerOutput timer(pcout, TimerOutput::summary, TimerOutput::wall_times);
  const auto start = std::chrono::steady_clock::now();

  double min_mass = std::numeric_limits<double>::max();
  for (const double m : store.mass)
    min_mass = std::min(min_mass, m);
  mass_tolerance = 1e-12 * min_mass;

  // The exact fields' largest L2 norms over the output times normalise the errors.
  if (compare_exact)
    for (double s = 0; s <= end_time * (1 + 1e-12); s += output_interval)
    {
      exact_displacement->set_time(s);
      exact_velocity->set_time(s);
      double nu = 0, nv = 0;
      for (std::size_t p = 0; p < store.size(); ++p)
        for (unsigned int d = 0; d < dim; ++d)
        {
          const double u = exact_displacement->value(store.reference_position[p], d);
          const double v = exact_velocity->value(store.reference_position[p], d);
          nu += store.initial_volume[p] * u * u;
          nv += store.initial_volume[p] * v * v;
        }
      exact_displacement_norm = std::max(exact_displacement_norm, std::sqrt(nu));
      exact_velocity_norm     = std::max(exact_velocity_norm, std::sqrt(nv));
      if (exact_stress)
      {
        exact_stress->set_time(s);
        double ns = 0;
        for (std::size_t p = 0; p < store.size(); ++p)
        {
          const auto e = exact_stress_at(store.reference_position[p]);
          ns += store.initial_volume[p] * (e * e);
        }
        exact_stress_norm = std::max(exact_stress_norm, std::sqrt(ns));
      }
    }
  exact_stress_norm       = std::max(exact_stress_norm, 1e-300);
  exact_displacement_norm = std::max(exact_displacement_norm, 1e-300);
  exact_velocity_norm     = std::max(exact_velocity_norm, 1e-300);

  // Only now, with every input checked, does the run write anything.
  std::filesystem::create_directories(output_directory);
  if (resumed)
  {
    // Drop the rows written after the checkpoint, then append.
    std::filesystem::resize_file(output_directory + "/history.csv", resumed_history_size);
    history.open(output_directory + "/history.csv", std::ios::app);
  }
  else
    history.open(output_directory + "/history.csv");
  AssertThrow(history, ExcBadInput("Output/Directory",
                                   "cannot write to '" + output_directory + "'"));
  if (!resumed)
  {
    history << "step,time,kinetic_energy,strain_energy,dissipated_energy,external_work,"
               "total_energy";
    for (const auto &c : constraints)
      for (const char *q : {"force", "displacement"})
        for (unsigned int d = 0; d < dim; ++d)
          history << "," << q << "_" << c->name() << "_" << axis[d];
    for (const auto &probe : probes)
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = i; j < dim; ++j)
          history << ",probe_" << probe.name << "_s" << axis[i] << axis[j];
    if (compare_exact)
      history << ",error_displacement_l2,error_velocity_l2";
    if (exact_stress)
      history << ",error_stress_l2";
    history << "\n";
  }

  pcout << "lme-mpm: " << dim << "D, " << store.size() << " particles, "
        << background.n_nodes() << " nodes, shape functions '" << shape_function->name()
        << "', dt = " << dt << " s, " << n_steps << " steps, " << n_threads_used
        << " thread(s)" << std::endl;

  std::string status = "completed", message;
  try
  {
    if (!resumed)
    {
      TimerOutput::Scope scope(timer, "output");
      write_output_row(false);
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
        write_output_row(step_count == n_steps);
        while (next_output_time <= t + 0.5 * dt)
          next_output_time += output_interval;
      }
      const bool by_steps =
          checkpoint_every_steps > 0 && step_count % checkpoint_every_steps == 0;
      const bool by_time = checkpoint_every_seconds > 0 &&
                           std::chrono::duration<double>(
                               std::chrono::steady_clock::now() - last_checkpoint)
                                   .count() >= checkpoint_every_seconds;
      if ((by_steps || by_time) && step_count < n_steps)
      {
        TimerOutput::Scope scope(timer, "checkpoint");
        write_checkpoint();
        last_checkpoint = std::chrono::steady_clock::now();
      }
      if (step_count % report_every == 0 || step_count == n_steps)
      {
        const double elapsed =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
                .count();
        pcout << "  step " << std::setw(8) << step_count << "  t = " << std::setw(12)
              << std::setprecision(5) << t << "  " << std::setw(3)
              << 100 * step_count / n_steps << "%  " << std::setprecision(3)
              << store.size() * step_count / elapsed << " particle-steps/s  ETA "
              << std::setprecision(3) << elapsed * (n_steps - step_count) / step_count
              << " s" << std::endl;
      }
    }
  }
  catch (const std::exception &e)
  {
    // Any failure inside the loop (an unstable step, a shape-function solve that does
    // not converge) ends the run with what it produced kept on disk.
    status = "aborted";
    if (dynamic_cast<const ExcRunAborted *>(&e) == nullptr)
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
      write_output_row(true);
    }
    catch (...)
    {
    }
  }

  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  results["wall_seconds"]              = wall;
  results["steps"]                     = step_count;
  results["particles"]                 = store.size();
  results["nodes"]                     = background.n_nodes();
  results["threads"]                   = n_threads_used;
  results["time_step"]                 = dt;
  results["particle_steps_per_second"] = store.size() * double(step_count) / wall;
  results["max_energy_drift"]          = max_energy_drift;
  if (peak_constraint < constraints.size())
  {
    results["peak_force"]           = peak_force;
    results["displacement_at_peak"] = displacement_at_peak;
  }
  if (compare_exact)
  {
    results["max_error_displacement_l2"] = max_error_displacement;
    results["max_error_velocity_l2"]     = max_error_velocity;
    if (exact_stress)
      results["max_error_stress_l2"] = max_error_stress;
  }
  for (const auto &s : shape_function->statistics())
    results["shape_function_" + s.first] = s.second;
  for (const auto &f : fracture_models)
    if (f)
      for (const auto &s : f->statistics())
        results[f->name() + "_" + s.first] = s.second;
  if (fracture_active)
  {
    std::size_t failed = 0;
    for (const auto f : store.failed)
      failed += f;
    results["failed_particles"]  = failed;
    results["dissipated_energy"] = energies()["dissipated_energy"];
    // The crack as a point set that scripts can read without a VTU parser.
    std::ofstream crack(output_directory + "/failed_particles.csv");
    crack << "id";
    for (unsigned int d = 0; d < dim; ++d)
      crack << ",x" << d;
    for (unsigned int d = 0; d < dim; ++d)
      crack << ",x0_" << d;
    crack << ",damage\n" << std::setprecision(10);
    for (std::size_t p = 0; p < store.size(); ++p)
      if (store.failed[p])
      {
        crack << store.id[p];
        for (unsigned int d = 0; d < dim; ++d)
          crack << ',' << store.position[p][d];
        for (unsigned int d = 0; d < dim; ++d)
          crack << ',' << store.reference_position[p][d];
        crack << ',' << store.damage[p] << '\n';
      }
  }
  if (!cracks.empty())
  {
    // The explicit cracks as grown: one row per polyline point.
    std::ofstream lines(output_directory + "/cracks.csv");
    lines << "crack,point";
    for (unsigned int d = 0; d < dim; ++d)
      lines << ",x" << d;
    lines << '\n' << std::setprecision(17);
    for (unsigned int l = 0; l < cracks.polylines().size(); ++l)
      for (unsigned int i = 0; i < cracks.polylines()[l].size(); ++i)
      {
        lines << l << ',' << i;
        for (unsigned int d = 0; d < dim; ++d)
          lines << ',' << cracks.polylines()[l][i][d];
        lines << '\n';
      }
    results["crack_second_fields"] = cracks.n_extra_nodes();
  }

  std::ofstream json(output_directory + "/summary.json");
  std::string quoted;
  for (const char c : message)
    quoted += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
  json << std::setprecision(10) << "{\n  \"status\": \"" << status << "\",\n"
       << "  \"message\": \"" << quoted << "\",\n"
       << "  \"shape_function\": \"" << shape_function->name() << "\",\n"
       << "  \"state_checksum\": \"" << std::hex << state_checksum() << std::dec
       << "\",\n"
       << "  \"dimension\": " << dim;
  for (const auto &r : results)
    json << ",\n  \"" << r.first << "\": " << r.second;
  json << "\n}\n";
  json.close();

  if (status != "completed")
  {
    // Past this point the output is on disk; the caller reports the failure.
    AssertThrow(false, ExcMessage(message));
  }
  pcout << "Finished: " << step_count << " steps in " << wall << " s ("
        << results["particle_steps_per_second"] << " particle-steps/s); max energy drift "
        << max_energy_drift << std::endl;
  return results;
}

template class Simulation<2>;
template class Simulation<3>;

// ------------------------------------------------------------------ entry points

void apply_overrides(ParameterHandler &prm, const std::vector<std::string> &overrides,
                     const bool skip_unknown)
{
  for (const auto &o : overrides)
  {
    const auto eq = o.find('=');
    AssertThrow(eq != std::string::npos,
                ExcBadInput("--set " + o, "expected 'Subsection/Entry=value'"));
    const auto path  = input::split(o.substr(0, eq), '/');
    const auto value = input::trim(o.substr(eq + 1));
    AssertThrow(!path.empty(), ExcBadInput("--set " + o, "no entry named"));
    for (std::size_t i = 0; i + 1 < path.size(); ++i)
      prm.enter_subsection(path[i]);
    try
    {
      prm.set(path.back(), value);
    }
    catch (const ParameterHandler::ExcEntryUndeclared &)
    {
      for (std::size_t i = 0; i + 1 < path.size(); ++i)
        prm.leave_subsection();
      AssertThrow(skip_unknown, ExcBadInput(o.substr(0, eq), "no such entry"));
      continue;
    }
    catch (const ParameterHandler::ExcValueDoesNotMatchPattern &e)
    {
      for (std::size_t i = 0; i + 1 < path.size(); ++i)
        prm.leave_subsection();
      AssertThrow(skip_unknown, ExcBadInput(o.substr(0, eq), input::concise_message(e)));
      continue;
    }
    for (std::size_t i = 0; i + 1 < path.size(); ++i)
      prm.leave_subsection();
  }
}

namespace
{
template <int dim>
std::map<std::string, double>
run_dim(const std::string &file, const std::vector<std::string> &overrides,
        const ParameterCounts &counts, std::ostream &console, const std::string &resume)
{
  ParameterHandler prm;
  Simulation<dim>::declare_parameters(prm, counts);
  prm.parse_input(file, "", false, false);
  apply_overrides(prm, overrides, false);
  Simulation<dim> simulation(prm, counts, console);
  if (!resume.empty())
    simulation.resume_from(resume);
  return simulation.run();
}
} // namespace

std::map<std::string, double>
run_parameter_file(const std::string &file, const std::vector<std::string> &overrides,
                   std::ostream &console, const std::string &resume)
{
  AssertThrow(std::filesystem::exists(file),
              ExcBadInput("parameter file", "'" + file + "' does not exist"));
  // First pass: how many materials, bodies, ... the file declares.
  ParameterCounts counts;
  {
    ParameterHandler prm;
    ParameterCounts::declare_parameters(prm);
    prm.parse_input(file, "", true, false);
    apply_overrides(prm, overrides, true);
    counts.parse_parameters(prm);
  }
  if (counts.dim == 2)
    return run_dim<2>(file, overrides, counts, console, resume);
  return run_dim<3>(file, overrides, counts, console, resume);
}

void print_default_parameters(std::ostream &out)
{
  ParameterHandler prm;
  Simulation<2>::declare_parameters(prm, ParameterCounts{2, 1, 1, 1, 1});
  prm.print_parameters(out, ParameterHandler::PRM);
}
} // namespace lme_mpm
