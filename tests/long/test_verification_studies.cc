// Long verification studies: convergence orders, gravity loading, 1e5 steps.
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
  // The sudden load excites every mode. The total energy's largest change over every
  // step (max_energy_drift, against the run's energy scale) falls in proportion to
  // the time step: 6.29e-3, 2.10e-3 and 6.32e-4 J at CFL 0.3, 0.1 and 0.03, at the
  // end of the four periods. (Measured at the history rows against the energy in play
  // so far, the drift was set by the first rows and seemed to fall as dt^2.)
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
  EXPECT_GT(drift_coarse / summary.at("max_energy_drift"), 2.5); // first order: 3
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
