// The stable time step: CFL times h_min / c_P whatever the end time (so that a run
// can be extended), only the last step shortened to land on the end time, and clear
// errors naming the entry when it cannot.
#include <gtest/gtest.h>

#include <lme_mpm/base/input.h>
#include <lme_mpm/solver/run_parameters.h>
#include <lme_mpm/solver/time_step_control.h>

#include <cmath>

using namespace lme_mpm;

namespace
{
std::string error_of(const RunParameters<2> &run, const double h, const double c)
{
  try
  {
    stable_time_step(run, h, c);
  }
  catch (const std::exception &e)
  {
    return input::concise_message(e);
  }
  return "";
}
} // namespace

TEST(StableTimeStep, CflStepDoesNotDependOnTheEndTime)
{
  RunParameters<2> run;
  run.cfl        = 0.3;
  const double h = 0.01, c = 2900; // 966.7 CFL steps to 1e-3 s
  for (const double end : {1e-3, 0.3e-3, 1.8e-3})
  {
    run.end_time          = end;
    const TimeStepping ts = stable_time_step(run, h, c);
    EXPECT_EQ(ts.dt, 0.3 * h / c);
    // The steps that reach the end time, the last of them shortened.
    EXPECT_GE(ts.dt * ts.n_steps, end * (1 - 1e-12));
    EXPECT_LT(ts.dt * (ts.n_steps - 1), end);
  }
  run.end_time = 1e-3;
  EXPECT_EQ(stable_time_step(run, h, c).n_steps, 967u);
}

TEST(StableTimeStep, FixedStepWithinTheLimitIsKept)
{
  RunParameters<2> run;
  run.fixed_time_step   = 1e-6;
  run.end_time          = 1e-4;
  const TimeStepping ts = stable_time_step(run, 0.01, 3000);
  EXPECT_EQ(ts.n_steps, 100u);
  EXPECT_NEAR(ts.dt, 1e-6, 1e-18);
}

TEST(StableTimeStep, EveryImpossibleStepNamesItsEntry)
{
  RunParameters<2> run;
  run.end_time        = 1;
  run.fixed_time_step = 1; // far beyond h / c
  EXPECT_NE(error_of(run, 0.01, 3000).find("Time/Time step"), std::string::npos);
  run.fixed_time_step = 0;
  run.cfl             = 1.5; // above Maximum CFL = 1
  EXPECT_NE(error_of(run, 0.01, 3000).find("Time/CFL"), std::string::npos);
  run.cfl = 0.3;
  // 3e10 steps.
  EXPECT_NE(error_of(run, 1e-7, 1e4).find("Time/End time"), std::string::npos);
  // A wave speed that is not finite: the materials are blamed.
  const std::string infinite =
      error_of(run, 0.01, std::numeric_limits<double>::infinity());
  EXPECT_EQ(infinite.rfind("Invalid input for 'the materials' entries': the P-wave "
                           "speed c_P = inf m/s",
                           0),
            0u)
      << infinite;
  // With the entries behind the wave speed: the unphysical one named first, with its
  // value.
  const std::vector<input::EntryValue> inputs =
      input::unphysical_first({{"Material 1/Density", 1000, "kg/m^3", 1, 1e5},
                               {"Material 1/E", 1e30, "Pa", 1e3, 1e13}});
  std::string message;
  try
  {
    stable_time_step(run, 0.01, 3e13, inputs);
  }
  catch (const std::exception &e)
  {
    message = input::concise_message(e);
  }
  EXPECT_EQ(
      message.rfind("Invalid input for 'Material 1/E': 'Material 1/E' = 1e+30 Pa "
                    "(outside its physical range 1000 to 1e+13 Pa) and 'Material "
                    "1/Density' = 1000 kg/m^3 give the P-wave speed c_P = 3e+13 m/s",
                    0),
      0u)
      << message;
}

TEST(TimeStepControl, SlowParticlesTakeTheWaveStepsAndTheLastLandsOnTheEnd)
{
  TimeStepping wave;
  wave.dt      = 1e-6 / 0.9675; // 967.5 steps to 1e-3 s
  wave.n_steps = 968;
  TimeStepControl clock;
  clock.set_up(wave, 1e-3, 0.01, 0.01);
  // 1 m/s moves 1e-6 m per step, far below 0.01 of a 1 cm cell.
  double t       = 0;
  unsigned int n = 0;
  while (!clock.finished(t, n))
  {
    const bool last = clock.last_step(t, n, 1.0);
    const double dt = clock.next(t, n, 1.0);
    EXPECT_EQ(last, n == 967u);
    if (!last)
    {
      EXPECT_EQ(dt, wave.dt);
    }
    t = clock.at_end() ? 1e-3 : t + dt;
    ++n;
  }
  EXPECT_EQ(n, 968u);
  EXPECT_EQ(t, 1e-3);
  EXPECT_EQ(clock.limited_steps(), 0u);
  EXPECT_EQ(clock.smallest_step(), wave.dt);
}

TEST(TimeStepControl, FastParticlesTravelAtMostTheLimitAndLandOnTheEnd)
{
  TimeStepping wave;
  wave.dt      = 1e-4;
  wave.n_steps = 100;
  TimeStepControl clock;
  const double h = 0.01, travel = 0.01, end = 1.01e-2;
  clock.set_up(wave, end, travel, h);
  // At 3 m/s the limit is 0.01 * 0.01 / 3 = 3.33e-5 s, a third of the wave step.
  double t       = 0;
  unsigned int n = 0;
  while (!clock.finished(t, n) && n < 1000)
  {
    const double dt = clock.next(t, n, 3.0);
    // (The last step takes what is left, within a billionth of a step of the limit.)
    EXPECT_LE(3.0 * dt, travel * h * (1 + 1e-9));
    // Every step the limit's but the last: none before it depends on the end time,
    // so a run extended past it takes the steps of one run to the later end.
    if (!clock.at_end())
    {
      EXPECT_EQ(dt, travel * h / 3.0);
    }
    t = clock.at_end() ? end : t + dt;
    ++n;
  }
  EXPECT_EQ(t, end);
  EXPECT_EQ(n, 303u); // 303 steps of 3.33e-5 s reach 1.01e-2 s
  EXPECT_EQ(clock.limited_steps(), n);
  EXPECT_NEAR(clock.smallest_step(), travel * h / 3.0, 1e-18);
  // Without a limit the wave step holds at any speed.
  TimeStepControl unlimited;
  unlimited.set_up(wave, end, 0, h);
  EXPECT_EQ(unlimited.next(0, 0, 1e6), wave.dt);
}

TEST(TimeStepControl, OnceLimitedTheStepDoesNotGrowAgain)
{
  TimeStepping wave;
  wave.dt      = 1e-4;
  wave.n_steps = 1000;
  TimeStepControl clock;
  clock.set_up(wave, 0.1, 0.01, 0.01);
  const double fast = clock.next(0, 0, 3.0); // 3.33e-5
  EXPECT_NEAR(fast, 1e-4 / 3, 1e-18);
  // The body turns and slows down: the step stays at the one the limit set.
  EXPECT_EQ(clock.next(fast, 1, 0.1), fast);
  // Faster still: shorter again.
  EXPECT_LT(clock.next(2 * fast, 2, 6.0), fast);
}
