// Grid, particle store, scatter determinism and the verification scenes.
#include <deal.II/base/multithread_info.h>

#include <gtest/gtest.h>

#include <lme_mpm/grid/background_grid.h>
#include <lme_mpm/output/particle_output.h>
#include <lme_mpm/output/probes.h>
#include <lme_mpm/particles/particle_store.h>

#include "test_helpers.h"

#include <cmath>
#include <filesystem>
#include <random>

using namespace lme_mpm;

TEST(BackgroundGrid, LexicographicNodesMatchDealIIVertices)
{
  BackgroundGrid<2> grid;
  grid.reinit(Point<2>(-1, 0), {{std::vector<double>(4, 0.5), {0.1, 0.2, 0.3}}});
  EXPECT_EQ(grid.n_nodes(), 5u * 4u);
  EXPECT_EQ(grid.n_cells(), 12u);
  EXPECT_FALSE(grid.is_uniform(1));
  // Every deal.II vertex DoF sits at the lexicographic node's position.
  for (const auto &cell : grid.dof_handler().active_cell_iterators())
    for (const unsigned int v : cell->vertex_indices())
    {
      const Point<2> p = cell->vertex(v);
      std::array<unsigned int, 2> ijk;
      ASSERT_TRUE(grid.locate(p, ijk));
      bool found = false;
      for (unsigned int n = 0; n < grid.n_nodes(); ++n)
        if (grid.node_point(n).distance(p) < 1e-12)
        {
          found = true;
          EXPECT_EQ(grid.dof(n, 0), cell->vertex_dof_index(v, 0));
          EXPECT_EQ(grid.dof(n, 1), cell->vertex_dof_index(v, 1));
        }
      EXPECT_TRUE(found);
    }
}

TEST(BackgroundGrid, LocateUniformAndGraded)
{
  BackgroundGrid<2> grid;
  grid.reinit(Point<2>(0, 0), {{std::vector<double>(10, 0.1), {0.1, 0.1, 0.2, 0.4}}});
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> ux(0, 1), uy(0, 0.8);
  for (int i = 0; i < 1000; ++i)
  {
    const Point<2> x(ux(rng), uy(rng));
    std::array<unsigned int, 2> ijk;
    ASSERT_TRUE(grid.locate(x, ijk));
    for (unsigned int d = 0; d < 2; ++d)
    {
      EXPECT_LE(grid.coordinates(d)[ijk[d]], x[d]);
      EXPECT_GE(grid.coordinates(d)[ijk[d] + 1], x[d]);
    }
  }
  std::array<unsigned int, 2> ijk;
  EXPECT_FALSE(grid.locate(Point<2>(-1e-9, 0.5), ijk));
  EXPECT_FALSE(grid.locate(Point<2>(0.5, 0.80001), ijk));
  EXPECT_TRUE(grid.locate(Point<2>(1.0, 0.8), ijk));
  EXPECT_EQ(ijk[0], 9u);
  EXPECT_EQ(ijk[1], 3u);
  EXPECT_EQ(grid.nodes_on_boundary(0).size(), 5u);
  EXPECT_EQ(grid.nodes_on_boundary(3).size(), 11u);
}

TEST(ParticleStore, CountingSortKeepsFieldsTogether)
{
  ParticleStore<2> store;
  std::mt19937 rng(7);
  for (unsigned int p = 0; p < 500; ++p)
  {
    store.add(Point<2>(p, 0), p + 1.0, 1.0, 0, 0);
    store.cell[p] = rng() % 37;
  }
  EXPECT_TRUE(store.sort_by_cell(37));
  for (std::size_t p = 0; p < store.size(); ++p)
  {
    if (p > 0)
    {
      EXPECT_LE(store.cell[p - 1], store.cell[p]);
      if (store.cell[p - 1] == store.cell[p]) // stable
      {
        EXPECT_LT(store.id[p - 1], store.id[p]);
      }
    }
    EXPECT_EQ(store.mass[p], store.id[p] + 1.0);
    EXPECT_EQ(store.position[p][0], double(store.id[p]));
  }
  const auto &off = store.cell_offsets();
  for (unsigned int c = 0; c < 37; ++c)
    for (std::size_t p = off[c]; p < off[c + 1]; ++p)
      EXPECT_EQ(store.cell[p], c);
  EXPECT_FALSE(store.sort_by_cell(37)); // already sorted: no reorder
}

namespace
{
/// Positions and velocities after a short two-disc run with a thread limit.
std::vector<double> disc_state(const unsigned int threads,
                               const std::vector<std::string> &extra = {})
{
  MultithreadInfo::set_thread_limit(threads);
  ParameterHandler prm;
  ParameterCounts counts;
  counts.bodies = 2;
  Simulation<2>::declare_parameters(prm, counts);
  prm.parse_input(lme_mpm_test::scene("two_disk_collision.prm"));
  std::vector<std::string> overrides = {"Output/Verbosity=0", "Time/End time=1.3",
                                        "Output/Directory=" +
                                            lme_mpm_test::scratch("threads")};
  overrides.insert(overrides.end(), extra.begin(), extra.end());
  apply_overrides(prm, overrides, false);
  std::ostringstream quiet;
  Simulation<2> sim(prm, counts, quiet);
  sim.run();
  std::vector<double> state;
  for (std::size_t p = 0; p < sim.particles().size(); ++p)
    for (unsigned int d = 0; d < 2; ++d)
      state.push_back(sim.particles().position[p][d]),
          state.push_back(sim.particles().velocity[p][d]);
  MultithreadInfo::set_thread_limit();
  return state;
}
} // namespace

TEST(Output, ParticleAndGridSeriesListEveryFileWritten)
{
  lme_mpm_test::run_scene("tension_bar.prm", "series",
                          {"Output/Write grid files=true",
                           "Output/Write particle files=true", "Time/End time=2e-5"});
  const std::string dir = lme_mpm_test::scratch_path("series");
  // The files a PVD record lists, each checked to exist.
  const auto listed = [&](const std::string &stem)
  {
    const std::string pvd = lme_mpm_test::file_text(dir + "/" + stem + ".pvd");
    unsigned int n        = 0;
    for (auto pos = pvd.find("file=\""); pos != std::string::npos;
         pos      = pvd.find("file=\"", pos + 1), ++n)
    {
      const auto begin = pos + 6, end = pvd.find('"', begin);
      EXPECT_TRUE(std::filesystem::exists(dir + "/" + pvd.substr(begin, end - begin)))
          << pvd.substr(begin, end - begin);
    }
    return n;
  };
  const unsigned int particle_files = listed("particles");
  EXPECT_GE(particle_files, 3u); // t = 0, 1e-5, 2e-5
  EXPECT_EQ(listed("grid"), particle_files);
  EXPECT_TRUE(std::filesystem::exists(dir + "/grid_00000.vtu"));
}

TEST(Output, ProbesReportTheEffectiveStress)
{
  // Three particles of equal volume and equal undamaged stress under one probe: intact,
  // half damaged and failed. The probe averages what the forces use: (1 + 0.5 + 0) / 3.
  ParameterHandler prm;
  Probes<2>::declare_parameters(prm, 1);
  prm.enter_subsection("Output");
  prm.enter_subsection("Probe 1");
  prm.set("Name", "p");
  prm.set("Point", "0, 0");
  prm.set("Radius", "1");
  prm.leave_subsection();
  prm.leave_subsection();
  Probes<2> probes;
  probes.parse_parameters(prm, 1);
  ParticleStore<2> store;
  for (unsigned int p = 0; p < 3; ++p)
  {
    store.add(Point<2>(0.1 * p, 0), 1.0, 2.0, 0, 0);
    store.stress[p][0][0] = 6e6;
    store.stress[p][0][1] = -3e6;
  }
  store.damage[1] = 0.5;
  store.damage[2] = 1;
  store.failed[2] = 1;
  std::ostringstream header, row;
  probes.write_header(header);
  probes.write_row(row, store);
  EXPECT_EQ(header.str(), ",probe_p_sxx,probe_p_sxy,probe_p_syy");
  const auto v = input::parse_doubles(row.str().substr(1), "probe row");
  ASSERT_EQ(v.size(), 3u);
  EXPECT_DOUBLE_EQ(v[0], 3e6);
  EXPECT_DOUBLE_EQ(v[1], -1.5e6);
  EXPECT_EQ(v[2], 0.0);
  // The one formula, which the particle files use too.
  EXPECT_EQ(effective_stress(store, 0), store.stress[0]);
  EXPECT_EQ(effective_stress(store, 1), 0.5 * store.stress[1]);
  EXPECT_EQ(effective_stress(store, 2).norm(), 0.0);
  store.damage[2] = 0.3; // failed whatever its damage
  EXPECT_EQ(effective_stress(store, 2).norm(), 0.0);
  const std::string dir = lme_mpm_test::scratch("effective_stress");
  std::filesystem::create_directories(dir);
  ParticleOutput<2>(dir).write(store, 0);
  const std::string vtu = lme_mpm_test::file_text(dir + "/particles_00000.vtu");
  for (const char *field : {"stress_xx", "undamaged_stress_xx", "max_principal_stress"})
    EXPECT_NE(vtu.find(std::string("Name=\"") + field + "\""), std::string::npos)
        << field;
}

TEST(Threads, ResultsBitwiseIndependentOfThreadCount)
{
  const auto one = disc_state(1), two = disc_state(2);
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t i = 0; i < one.size(); ++i)
    ASSERT_EQ(one[i], two[i]) << "entry " << i;
}

TEST(ActiveNodes, EmptyGridRegionsChangeNothing)
{
  // Nodal loops run over the nodes that carry mass only: a grid three times as wide,
  // the extra part empty, gives the same bits (particles keep their order, since the
  // extension adds cells at the end of each row).
  const auto narrow = disc_state(1), wide = disc_state(1, {"Grid/Upper corner=3, 1"});
  ASSERT_EQ(narrow.size(), wide.size());
  for (std::size_t i = 0; i < narrow.size(); ++i)
    ASSERT_EQ(narrow[i], wide[i]) << "entry " << i;
}

TEST(VibratingBar, LinearErrorBoundAndConvergence)
{
  // Acceptance: error at most 0.02, falling by at least 1.5x per halving of h.
  std::vector<double> errors;
  for (const char *h : {"0.05", "0.025", "0.0125"})
  {
    const auto r = lme_mpm_test::run_scene(
        "vibrating_bar.prm", "bar",
        {std::string("Grid/Cell size=") + h, "Output/Write particle files=false"});
    errors.push_back(r.at("max_error_displacement_l2"));
    EXPECT_LT(r.at("max_energy_drift"), 1e-3);
  }
  for (std::size_t i = 0; i < errors.size(); ++i)
    EXPECT_LE(errors[i], 0.02) << "level " << i;
  for (std::size_t i = 1; i < errors.size(); ++i)
    EXPECT_GE(errors[i - 1] / errors[i], 1.5) << "levels " << i - 1 << ", " << i;
  // Observed order (printed for the record): about 2 for this smooth, small-strain case.
  std::cout << "vibrating bar (linear): errors " << errors[0] << " " << errors[1] << " "
            << errors[2] << ", order " << std::log2(errors[1] / errors[2]) << std::endl;
}

TEST(TwoDiscCollision, EnergyConservedAndDiscsBounceApart)
{
  ParameterHandler prm;
  ParameterCounts counts;
  counts.bodies = 2;
  Simulation<2>::declare_parameters(prm, counts);
  prm.parse_input(lme_mpm_test::scene("two_disk_collision.prm"));
  apply_overrides(prm,
                  {"Output/Verbosity=0", "Output/Write particle files=false",
                   "Output/Directory=" + lme_mpm_test::scratch("discs")},
                  false);
  std::ostringstream quiet;
  Simulation<2> sim(prm, counts, quiet);
  const auto summary = sim.run();
  EXPECT_LT(summary.at("max_energy_drift"), 0.03);
  std::cout << "two discs (scene default shape functions): max energy drift "
            << summary.at("max_energy_drift") << std::endl;
  // Momentum of each disc after the impact: they move apart along the diagonal.
  Tensor<1, 2> momentum[2];
  for (std::size_t p = 0; p < sim.particles().size(); ++p)
    momentum[sim.particles().body_id[p]] +=
        sim.particles().mass[p] * sim.particles().velocity[p];
  EXPECT_LT(momentum[0][0], 0);
  EXPECT_LT(momentum[0][1], 0);
  EXPECT_GT(momentum[1][0], 0);
  EXPECT_GT(momentum[1][1], 0);
  // Total momentum stays zero (equal and opposite discs).
  EXPECT_LT((momentum[0] + momentum[1]).norm(), 1e-9 * momentum[0].norm());
}

TEST(VibratingBar, LmeBeatsLinearAndConvergesAtSecondOrder)
{
  // Acceptance (issue 3): LME gamma = 1.8 has a lower error than linear on the same
  // grid and an observed order of at least 1.8 over three refinements.
  std::vector<double> lme, linear;
  for (const char *h : {"0.05", "0.025", "0.0125", "0.00625"})
    for (const char *type : {"lme", "linear"})
    {
      const auto r = lme_mpm_test::run_scene(
          "vibrating_bar.prm", std::string("bar_") + type,
          {std::string("Grid/Cell size=") + h,
           std::string("Shape functions/Type=") + type, "Shape functions/LME gamma=1.8",
           "Output/Write particle files=false"});
      (std::string(type) == "lme" ? lme : linear)
          .push_back(r.at("max_error_displacement_l2"));
    }
  for (std::size_t i = 0; i < lme.size(); ++i)
  {
    EXPECT_LT(lme[i], linear[i]) << "level " << i;
    if (i > 0)
    {
      const double order = std::log2(lme[i - 1] / lme[i]);
      std::cout << "LME order between levels " << i - 1 << " and " << i << ": " << order
                << std::endl;
      EXPECT_GE(order, 1.8) << "levels " << i - 1 << ", " << i;
    }
  }
}

TEST(VibratingBar, ThreeDimensionsMatchTwo)
{
  // With nu = 0 and rollers, the 3D bar is the 2D one: same errors at the same h.
  for (const char *type : {"linear", "lme"})
  {
    const std::vector<std::string> o = {std::string("Shape functions/Type=") + type,
                                        "Grid/Cell size=0.05",
                                        "Output/Write particle files=false"};
    const auto r3 = lme_mpm_test::run_scene("vibrating_bar_3d.prm", "bar3d", o);
    const auto r2 = lme_mpm_test::run_scene("vibrating_bar.prm", "bar2d", o);
    // Linear: identical arithmetic. LME: the 1e-6 support cut-off drops different tail
    // nodes from a sphere than from a circle, a perturbation of order 1e-6 * N.
    const double tolerance = std::string(type) == "linear" ? 1e-9 : 1e-3;
    EXPECT_NEAR(r3.at("max_error_displacement_l2") / r2.at("max_error_displacement_l2"),
                1.0, tolerance)
        << type << ": 3D " << r3.at("max_error_displacement_l2") << ", 2D "
        << r2.at("max_error_displacement_l2");
    EXPECT_LT(r3.at("max_error_displacement_l2"), 0.02) << type;
  }
}

TEST(Gravity, ReactionBalancesWeightAndProbeSeesHydrostaticStress)
{
  // A column 1 m wide, 2 m high, rho = 2000 kg/m^3, 0.5 m thick, released under
  // g = 10 m/s^2 on a fixed base with roller sides. Undamped, it oscillates about the
  // static state: over whole periods (T = 4 H / c) the base reaction averages the weight
  // and the stress at mid-height averages -rho g (H - y). Energy including the work of
  // gravity is conserved.
  const std::string file = lme_mpm_test::scratch("gravity") + ".prm";
  std::ofstream(file) << R"(
subsection Problem
  set Number of bodies = 1
  set Thickness = 0.5
  set Body force = 0, -10
end
subsection Grid
  set Lower corner = 0, 0
  set Upper corner = 1, 2.5
  set Cell size = 0.05
end
subsection Time
  set End time = 0.45254833995939   # four periods, T = 4 H / c, c = sqrt(E / rho)
  set CFL = 0.3
end
subsection Material 1
  set Density = 2000
  subsection linear elastic
    set Young's modulus = 1e7
    set Poisson's ratio = 0
  end
end
subsection Body 1
  set Shape = rectangle(0, 0, 1, 2)
end
subsection Boundary conditions
  set Number of constraints = 2
  subsection Constraint 1
    set Name = base
    set Boundary ids = 2
    set Components = x, y
  end
  subsection Constraint 2
    set Name = sides
    set Boundary ids = 0, 1
    set Components = x
  end
end
subsection Output
  set Output interval = 0.0011313708498985
  set Write particle files = false
  set Number of probes = 1
  subsection Probe 1
    set Name = mid
    set Point = 0.5, 1
    set Radius = 0.06
  end
end
)";
  const std::string out = lme_mpm_test::scratch("gravity_out");
  std::ostringstream quiet;
  // The sudden load excites every mode, so the true energy (not the scheme's shadow
  // energy) fluctuates by O(dt^2): check that it converges at that rate.
  const double drift_coarse =
      run_parameter_file(file, {"Output/Directory=" + out, "Time/CFL=0.3"}, quiet)
          .at("max_energy_drift");
  const auto summary =
      run_parameter_file(file, {"Output/Directory=" + out, "Time/CFL=0.1"}, quiet);
  std::ifstream in(out + "/history.csv");
  std::string line;
  std::getline(in, line);
  const auto names = input::split(line, ',');
  const auto col   = [&](const std::string &n)
  { return std::find(names.begin(), names.end(), n) - names.begin(); };
  double force = 0, stress = 0;
  unsigned int n = 0;
  std::vector<double> last;
  while (std::getline(in, line))
  {
    const auto v = input::parse_doubles(line, "history.csv");
    if (n > 0) // skip t = 0 so the rows cover whole periods once
      force += v[col("force_base_y")], stress += v[col("probe_mid_syy")];
    ++n;
    last = v;
  }
  force /= (n - 1), stress /= (n - 1);
  const double weight = 2000 * 10 * 1 * 2 * 0.5;
  EXPECT_NEAR(force / weight, 1.0, 0.01) << force;
  EXPECT_NEAR(stress / (-2000 * 10 * 1.0), 1.0, 0.03) << stress;
  EXPECT_LT(summary.at("max_energy_drift"), 2e-3);
  EXPECT_GT(drift_coarse / summary.at("max_energy_drift"), 6.0); // dt^2 would give 9
  EXPECT_GT(last[col("external_work")], 0);                      // gravity did work
}

namespace
{
/// Resident memory of this process in bytes (Linux).
std::size_t resident_bytes()
{
  std::ifstream statm("/proc/self/statm");
  std::size_t size = 0, resident = 0;
  statm >> size >> resident;
  return resident * static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
}
} // namespace

TEST(LongRun, HundredThousandStepsWithoutGrowthAndWithBoundedEnergy)
{
  // The vibrating bar at h = 0.05 (160 particles, LME) for 1e5 steps: about 375
  // periods. Memory must not grow between the first and the last 5e4 steps, and the
  // energy of the undamped bar must stay bounded.
  MultithreadInfo::set_thread_limit(1);
  ParameterHandler prm;
  ParameterCounts counts;
  counts.constraints = 2;
  Simulation<2>::declare_parameters(prm, counts);
  prm.parse_input(lme_mpm_test::scene("vibrating_bar.prm"));
  const double dt = 0.3 * 0.05 / std::sqrt(1e8 / 1000);
  apply_overrides(prm,
                  {"Output/Verbosity=0", "Grid/Cell size=0.05",
                   "Shape functions/Type=lme", "Time/Time step=" + std::to_string(dt),
                   "Time/End time=" + std::to_string(1e5 * dt),
                   "Output/Directory=" + lme_mpm_test::scratch("long")},
                  false);
  std::ostringstream quiet;
  Simulation<2> sim(prm, counts, quiet);
  const double e0      = sim.energies().at("kinetic_energy");
  std::size_t rss_half = 0;
  double e_max = 0, e_min = 1e300;
  for (unsigned int s = 0; s < 100000; ++s)
  {
    sim.step();
    if (s == 50000)
      rss_half = resident_bytes();
    if (s % 1000 == 0)
    {
      const auto e       = sim.energies();
      const double total = e.at("kinetic_energy") + e.at("strain_energy");
      e_max = std::max(e_max, total), e_min = std::min(e_min, total);
    }
  }
  const std::size_t rss_end = resident_bytes();
  std::cout << "long run: resident " << rss_half / 1024 << " kB after 5e4 steps, "
            << rss_end / 1024 << " kB after 1e5; energy in [" << e_min / e0 << ", "
            << e_max / e0 << "] of the initial" << std::endl;
  EXPECT_LE(rss_end, rss_half + 256 * 1024); // no growth beyond allocator noise
  EXPECT_LT(e_max / e0, 1.01);
  EXPECT_GT(e_min / e0, 0.99);
  MultithreadInfo::set_thread_limit();
}
