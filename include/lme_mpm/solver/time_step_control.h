#ifndef LME_MPM_SOLVER_TIME_STEP_CONTROL_H
#define LME_MPM_SOLVER_TIME_STEP_CONTROL_H

#include <lme_mpm/solver/run_parameters.h>

#include <algorithm>
#include <limits>

namespace lme_mpm
{
/**
 * The length of each step. The stable step of the wave speed (TimeStepping: CFL or
 * fixed) holds unless the fastest particle would travel more than a fraction
 * `travel` of the smallest cell in it (Time/Particle travel per step): the explicit
 * update evaluates the shape functions at the start-of-step positions for the whole
 * step, and its error grows with that travel (doc/stability.md). A run in which the
 * limit never binds takes the wave steps; in one in which it does, the step does not
 * grow again after the limit has set it (next()). Only the last step depends on the
 * end time, shortened to land on it: a run extended from a checkpoint taken before
 * that step takes the steps one run to the later end time would.
 */
class TimeStepControl
{
public:
  void set_up(const TimeStepping &wave, const double end_time, const double travel,
              const double h_min)
  {
    wave_dt    = wave.dt;
    wave_steps = wave.n_steps;
    end        = end_time;
    max_travel = travel * h_min;
  }

  /// The step the wave speed and the travel limit allow at the particle speed @p v.
  double allowed(const double v) const
  {
    return max_travel > 0 && v * wave_dt > max_travel ? max_travel / v : wave_dt;
  }

  /// True if the step from time @p t after @p steps steps, with the fastest particle
  /// at @p max_speed, is the run's last (next() shortens it to end on the end time).
  bool last_step(const double t, const unsigned int steps, const double max_speed) const
  {
    const double dt = step_at(max_speed);
    return dt < wave_dt ? t + dt >= end - 1e-9 * wave_dt : steps + 1 >= wave_steps;
  }

  /**
   * The step from time @p t after @p steps steps when the fastest particle moves at
   * @p max_speed. Once the limit has bound, the step never grows again: a step that
   * breathes with the motion (short while the body is fast, long while it turns)
   * pumps energy into a vibration through the central-difference update (the bar at
   * 0.1 c with B-splines: 2.9 % over three periods against 2e-4 at the constant short
   * step). The last step ends on the end time.
   */
  double next(const double t, const unsigned int steps, const double max_speed)
  {
    ending    = last_step(t, steps, max_speed);
    double dt = step_at(max_speed);
    if (dt < wave_dt)
    {
      ++n_limited;
      held_dt = dt;
    }
    smallest_dt = std::min(smallest_dt, dt);
    return ending ? std::max(0.0, end - t) : dt;
  }

  /// True once the step next() gave last was the run's last: the run is at its end.
  bool at_end() const { return ending; }
  /// True once the run has reached its end time after @p steps steps.
  bool finished(const double t, const unsigned int steps) const
  {
    return ending || (n_limited == 0 ? steps >= wave_steps : t >= end - 1e-9 * wave_dt);
  }

  double wave_step() const { return wave_dt; }
  /// The steps the run takes where the limit never binds.
  unsigned int planned_steps() const { return wave_steps; }
  double end_time() const { return end; }
  /// The shortest step but the last, which lands on the end time.
  double smallest_step() const { return std::min(smallest_dt, wave_dt); }
  /// Steps shortened by the travel limit so far.
  unsigned long long limited_steps() const { return n_limited; }

  template <class Archive>
  void serialize(Archive &ar)
  {
    ar(n_limited, smallest_dt, held_dt);
  }

private:
  double wave_dt = 0, end = 0, max_travel = 0;
  unsigned int wave_steps      = 0;
  unsigned long long n_limited = 0;
  double smallest_dt           = std::numeric_limits<double>::max();
  /// The shortest step the limit has set (steps never grow past it again).
  double held_dt = std::numeric_limits<double>::max();
  /// The last step given was the run's last.
  bool ending = false;

  /// The step the limit and the steps before allow at the particle speed @p v.
  double step_at(const double v) const
  {
    return std::min(allowed(v), n_limited > 0 ? held_dt : wave_dt);
  }
};
} // namespace lme_mpm

#endif
