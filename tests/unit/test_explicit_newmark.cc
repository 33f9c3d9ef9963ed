// ExplicitNewmark on a single oscillator: order and energy.
#include <gtest/gtest.h>

#include <lme_mpm/solver/explicit_newmark.h>

#include <cmath>
#include <iostream>

namespace
{
/// Integrates to time T with n steps; returns the error in x(T) and v(T).
std::pair<double, double> oscillator_error(const double gamma, const unsigned int n,
                                           double *energy_drift = nullptr)
{
  const lme_mpm::ExplicitNewmark newmark{gamma};
  const double omega = 2.0, T = 3.0, dt = T / n;
  double x = 1.0, v = 0.0, a = -omega * omega * x, drift = 0;
  for (unsigned int i = 0; i < n; ++i)
  {
    x += dt * newmark.displacement_rate(v, a, dt);
    const double a_new = -omega * omega * x;
    v                  = newmark.corrected_velocity(v, a, a_new, dt);
    a                  = a_new;
    const double e     = 0.5 * v * v + 0.5 * omega * omega * x * x;
    drift              = std::max(drift, std::abs(e - 0.5 * omega * omega));
  }
  if (energy_drift)
    *energy_drift = drift / (0.5 * omega * omega);
  return {std::abs(x - std::cos(omega * T)), std::abs(v + omega * std::sin(omega * T))};
}
} // namespace

TEST(ExplicitNewmark, SecondOrderAtGammaHalf)
{
  const auto coarse = oscillator_error(0.5, 200), fine = oscillator_error(0.5, 400);
  const double order_x = std::log2(coarse.first / fine.first);
  const double order_v = std::log2(coarse.second / fine.second);
  EXPECT_NEAR(order_x, 2.0, 0.1);
  EXPECT_NEAR(order_v, 2.0, 0.1);
  EXPECT_LT(fine.first, 1e-3);
}

TEST(ExplicitNewmark, FirstOrderAndDissipativeAboveHalf)
{
  const auto coarse = oscillator_error(0.75, 200), fine = oscillator_error(0.75, 400);
  EXPECT_NEAR(std::log2(coarse.first / fine.first), 1.0, 0.15);
}

TEST(ExplicitNewmark, EnergyBoundedAtGammaHalf)
{
  // Central differences conserve a shadow energy: the true one oscillates by O(dt^2)
  // and does not grow over many periods.
  double drift_short = 0, drift_long = 0;
  oscillator_error(0.5, 300, &drift_short);
  const lme_mpm::ExplicitNewmark newmark{0.5};
  const double omega = 2.0, dt = 0.01;
  double x = 1.0, v = 0.0, a = -omega * omega;
  for (unsigned int i = 0; i < 200000; ++i)
  {
    x += dt * newmark.displacement_rate(v, a, dt);
    const double a_new = -omega * omega * x;
    v                  = newmark.corrected_velocity(v, a, a_new, dt);
    a                  = a_new;
    drift_long = std::max(drift_long, std::abs(0.5 * v * v + 2 * x * x - 2.0) / 2.0);
  }
  EXPECT_LT(drift_short, 1e-3);
  EXPECT_LT(drift_long, 1e-3);
}
