// The start of the scheme, a^0 = M^-1 f(u^0), on whole runs.
#include <deal.II/base/parameter_handler.h>

#include <gtest/gtest.h>

#include "test_helpers.h"

#include <cmath>
#include <iostream>

namespace
{
/// A 2D elastic block (E = 1e6 Pa, nu = 0.3, rho = 1000, c_P = 36.7 m/s) on linear
/// shape functions, with @p extra entries (subsection text) appended.
std::unique_ptr<lme_mpm::Simulation<2>> block(const std::string &extra,
                                              const unsigned int n_constraints,
                                              std::ostringstream &quiet)
{
  using namespace lme_mpm;
  dealii::ParameterHandler prm; // the simulation keeps no reference to it
  ParameterCounts counts;
  counts.constraints = n_constraints;
  Simulation<2>::declare_parameters(prm, counts);
  prm.parse_input_from_string("subsection Boundary conditions\n"
                              "  set Number of constraints = " +
                              std::to_string(n_constraints) +
                              "\nend\n"
                              "subsection Material 1\n"
                              "  subsection linear elastic\n"
                              "    set Young's modulus = 1e6\n"
                              "    set Poisson's ratio = 0.3\n"
                              "  end\n"
                              "end\n"
                              "subsection Output\n"
                              "  set Verbosity = 0\n"
                              "  set Write particle files = false\n"
                              "  set Directory = " +
                              lme_mpm_test::scratch("newmark_start") + "\nend\n" + extra);
  return std::make_unique<Simulation<2>>(prm, counts, quiet);
}

/// Particle displacements of a column hanging under gravity from its fixed base,
/// after 0.1 s with time step @p dt.
std::vector<double> sagging_column(const double dt)
{
  std::ostringstream quiet;
  auto sim = block("subsection Problem\n  set Body force = 0, -10\nend\n"
                   "subsection Grid\n  set Lower corner = 0, 0\n"
                   "  set Upper corner = 0.2, 1.2\n  set Cell size = 0.05\nend\n"
                   "subsection Body 1\n  set Shape = rectangle(0.05, 0, 0.15, 1)\nend\n"
                   "subsection Time\n  set End time = 0.1\n  set Time step = " +
                       std::to_string(dt) +
                       "\nend\n"
                       "subsection Boundary conditions\n  subsection Constraint 1\n"
                       "    set Name = base\n    set Boundary ids = 2\n"
                       "    set Components = x, y\n  end\nend\n",
                   1, quiet);
  sim->run();
  std::vector<double> u;
  const auto &store = sim->particles();
  for (std::size_t p = 0; p < store.size(); ++p)
    for (unsigned int d = 0; d < 2; ++d)
      u.push_back(store.position[p][d] - store.reference_position[p][d]);
  return u;
}
} // namespace

TEST(NewmarkStart, FreeFallIsExact)
{
  // A body falling freely in an empty grid has constant acceleration g, which the
  // explicit Newmark scheme integrates exactly, provided it starts from a^0 = g.
  std::ostringstream quiet;
  auto sim = block("subsection Problem\n  set Body force = 0, -10\nend\n"
                   "subsection Grid\n  set Lower corner = 0, -1\n"
                   "  set Upper corner = 1, 1\n  set Cell size = 0.1\nend\n"
                   "subsection Body 1\n  set Shape = rectangle(0.3, 0.5, 0.7, 0.9)\nend\n"
                   "subsection Time\n  set End time = 0.2\n  set Time step = 1e-3\nend\n",
                   0, quiet);
  sim->run();
  const double t = sim->time(), g = -10;
  ASSERT_NEAR(t, 0.2, 1e-15);
  const auto &store = sim->particles();
  double max_du = 0, max_dv = 0;
  for (std::size_t p = 0; p < store.size(); ++p)
  {
    const double u = store.position[p][1] - store.reference_position[p][1];
    max_du         = std::max(max_du, std::abs(u - 0.5 * g * t * t) / (0.5 * -g * t * t));
    max_dv         = std::max(max_dv, std::abs(store.velocity[p][1] - g * t) / (-g * t));
    EXPECT_NEAR(store.acceleration[p][1], g, 1e-10);
  }
  std::cout << "largest relative error: displacement " << max_du << ", velocity "
            << max_dv << "\n";
  EXPECT_LT(max_du, 1e-10);
  EXPECT_LT(max_dv, 1e-10);
}

TEST(NewmarkStart, RampedFreeFallIsExact)
{
  // Gravity ramped up over t_r (Problem/Body force ramp time): the acceleration is
  // piecewise linear in time, the fall a cubic and then a parabola. The trapezoidal
  // rule integrates the velocity exactly; the position update u + dt v + dt^2/2 a
  // misses dt^3/6 of the jerk g/t_r on each step of the ramp, t_r dt^2 (g/t_r) / 6 =
  // g dt^2 / 6 in all: the displacement must be off by exactly that.
  std::ostringstream quiet;
  const double g = -10, ramp = 0.1;
  auto sim =
      block("subsection Problem\n  set Body force = 0, -10\n"
            "  set Body force ramp time = 0.1\nend\n"
            "subsection Grid\n  set Lower corner = 0, -1\n"
            "  set Upper corner = 1, 1\n  set Cell size = 0.1\nend\n"
            "subsection Body 1\n  set Shape = rectangle(0.3, 0.5, 0.7, 0.9)\nend\n"
            "subsection Time\n  set End time = 0.25\n  set Time step = 1e-3\nend\n",
            0, quiet);
  sim->run();
  const double t = sim->time();
  ASSERT_NEAR(t, 0.25, 1e-14);
  const double u_exact = g * (0.5 * t * t - 0.5 * t * ramp + ramp * ramp / 6),
               v_exact = g * (t - 0.5 * ramp);
  const double dt = 1e-3, truncation = -g * dt * dt / 6;
  const auto &store = sim->particles();
  double max_du = 0, max_dv = 0;
  for (std::size_t p = 0; p < store.size(); ++p)
  {
    const double u = store.position[p][1] - store.reference_position[p][1];
    max_du         = std::max(max_du, std::abs((u - u_exact) / truncation - 1));
    max_dv         = std::max(max_dv, std::abs(store.velocity[p][1] / v_exact - 1));
  }
  std::cout << "ramped fall: displacement error / (g dt^2 / 6) - 1 at most " << max_du
            << ", relative velocity error " << max_dv << "\n";
  EXPECT_LT(max_du, 1e-6);
  EXPECT_LT(max_dv, 1e-10);
}

TEST(NewmarkStart, GravityLoadedColumnConvergesAtSecondOrderInTime)
{
  // The same grid and particles at three time steps: the differences between
  // successive solutions shrink four times per halving (first order, twice, if the
  // scheme started from a^0 = 0).
  const auto u1 = sagging_column(1e-3), u2 = sagging_column(5e-4),
             u4 = sagging_column(2.5e-4);
  double d12 = 0, d24 = 0, scale = 0;
  for (std::size_t i = 0; i < u1.size(); ++i)
  {
    d12 += std::pow(u1[i] - u2[i], 2);
    d24 += std::pow(u2[i] - u4[i], 2);
    scale += u4[i] * u4[i];
  }
  ASSERT_GT(d24, 1e-12 * scale); // the time error is visible at all
  const double order = 0.5 * std::log2(d12 / d24);
  std::cout << "time-step order " << order << "\n";
  EXPECT_NEAR(order, 2.0, 0.15) << "time-step order of the displacements";
}

TEST(NewmarkStart, DrivenNodesCarryParticlesOnThePrescribedVelocity)
{
  // Every node driven at v = c t^2: the particles must move with the prescribed
  // velocity. Accelerations from the velocity change over the step (its mean)
  // would leave them O(dt) behind while it accelerates.
  std::ostringstream quiet;
  const double c = 0.5;
  auto sim =
      block("subsection Grid\n  set Lower corner = 0, 0\n"
            "  set Upper corner = 2, 1\n  set Cell size = 0.1\nend\n"
            "subsection Body 1\n  set Shape = rectangle(0.2, 0.2, 0.8, 0.8)\nend\n"
            "subsection Time\n  set End time = 1\n  set Time step = 1e-3\nend\n"
            "subsection Boundary conditions\n  subsection Constraint 1\n"
            "    set Name = all\n    set Box = -1, -1, 3, 2\n    set Components = x\n"
            "    subsection Velocity\n      set Function expression = 0.5*t^2; 0\n"
            "    end\n  end\nend\n",
            1, quiet);
  sim->run();
  const double t    = sim->time();
  const auto &store = sim->particles();
  double max_dv = 0, max_da = 0;
  for (std::size_t p = 0; p < store.size(); ++p)
  {
    max_dv = std::max(max_dv, std::abs(store.velocity[p][0] / (c * t * t) - 1));
    max_da = std::max(max_da, std::abs(store.acceleration[p][0] / (2 * c * t) - 1));
  }
  std::cout << "largest relative error: velocity " << max_dv << ", acceleration "
            << max_da << "\n";
  EXPECT_LT(max_dv, 1e-8);
  EXPECT_LT(max_da, 1e-8);
}
