#ifndef LME_MPM_BASE_STAGE_TIMER_H
#define LME_MPM_BASE_STAGE_TIMER_H

#include <chrono>
#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace lme_mpm
{
/**
 * Wall time per stage of a time step, cheap enough to stay on: one steady-clock
 * read when a stage starts and one when it ends (tens of nanoseconds, where deal.II's
 * TimerOutput also reads the CPU clock, a system call). Stages nest: entering one
 * pauses the stage around it, so the stages' times add up to the time spent in them
 * and a stage called from several places (contact) is one row of the table.
 */
class StageTimer
{
public:
  using Clock = std::chrono::steady_clock;

  /// Adds a stage; returns its handle. The table lists stages in this order.
  unsigned int add(const std::string &name);

  /// Times a stage for the scope's lifetime.
  class Scope
  {
  public:
    Scope(StageTimer &timer, unsigned int stage) : timer(timer), outer(timer.current)
    {
      const Clock::time_point now = Clock::now();
      timer.charge(now);
      timer.current = stage;
      ++timer.calls[stage];
    }
    ~Scope()
    {
      timer.charge(Clock::now());
      timer.current = outer;
    }
    Scope(const Scope &)            = delete;
    Scope &operator=(const Scope &) = delete;

  private:
    StageTimer &timer;
    int outer;
  };

  /// Seconds per stage, by name.
  std::map<std::string, double> seconds() const;
  /// Seconds of the stage with handle @p stage.
  double seconds(const unsigned int stage) const
  {
    return std::chrono::duration<double>(elapsed[stage]).count();
  }
  /// Adds "stage_seconds_<name>" (lower case, words joined by '_') for every stage
  /// that ran.
  void add_results(std::map<std::string, double> &results) const;
  /// The table: stage, calls, wall time and share of @p total seconds.
  void print(std::ostream &out, double total) const;

private:
  // Adds the time since the last clock read to the running stage.
  void charge(const Clock::time_point now)
  {
    if (current >= 0)
      elapsed[current] += now - last;
    last = now;
  }

  std::vector<std::string> names;
  std::vector<Clock::duration> elapsed;
  std::vector<unsigned long> calls;
  int current = -1;
  Clock::time_point last;
};
} // namespace lme_mpm

#endif
