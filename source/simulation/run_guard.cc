#include <lme_mpm/base/format.h>
#include <lme_mpm/base/input.h>
#include <lme_mpm/base/interrupt.h>
#include <lme_mpm/simulation/run_guard.h>

#include <cmath>
#include <sstream>

namespace lme_mpm
{
namespace
{
const char *const left_the_grid = "the particle left the background grid (enlarge the "
                                  "grid, or the run is unstable: lower the CFL number)";
} // namespace

template <int dim>
void RunGuard<dim>::stop_if_lost(const std::size_t p, const unsigned int step,
                                 const double t) const
{
  if (p >= particles.size())
    return;
  // On several ranks this rank alone knows: not an exception every rank ends with
  // (end_failed_run() would gather from ranks that are not there), so the program
  // stops them all (main.cc).
  AssertThrow(!ranks.distributed(),
              dealii::ExcMessage("Run stopped at step " + std::to_string(step) +
                                 ": particle " + std::to_string(particles.id[p]) +
                                 " at " + point_to_string(particles.position[p]) +
                                 " is outside the background grid"));
  AssertThrow(false,
              ExcRunAborted(step, t, particles.id[p],
                            point_to_string(particles.position[p]), left_the_grid));
}

template <int dim>
void RunGuard<dim>::stop_if_unstable(const std::size_t p, const bool on_some_rank,
                                     const unsigned int step, const double t) const
{
  if (!on_some_rank)
    return;
  stop_if_any(p, step, t,
              [this](const std::size_t bad) -> std::string
              {
                if (!std::isfinite(particles.velocity[bad].norm_square()))
                  return "non-finite velocity (the run is unstable: lower the CFL "
                         "number)";
                if (!grid.inside(particles.position[bad]))
                  return left_the_grid;
                if (!(particles.density[bad] > 0))
                  return "non-positive density (the material is inverted: the run is "
                         "unstable, lower the CFL number, or the deformation is too "
                         "large for a small-strain model)";
                return "the particle moved more than half a cell in one step (the run "
                       "is unstable or the time step too large: lower the CFL number)";
              });
}

template <int dim>
void RunGuard<dim>::stop_if_energy_runs_away(const double drift,
                                             const unsigned int limited_steps,
                                             const unsigned int step,
                                             const double t) const
{
  // Without a travel-limited step a blow-up moves some particle half a cell in a step
  // (stop_if_unstable); the same on every rank, so no reduction is spent on it.
  if (limited_steps == 0)
    return;
  const double d = ranks.max(drift);
  if (!(d > 0.5))
    return;
  std::ostringstream msg;
  msg << "Run stopped at step " << step << ", time " << t
      << ": the total energy has drifted by " << d
      << " of the run's energy scale (kinetic + strain + dissipated energy and "
         "external work), more than half: the run is unstable (lower the CFL number)";
  AssertThrow(false, ExcRunStopped(msg.str()));
}

template <int dim>
void RunGuard<dim>::stop_if_interrupted(const int signal, const unsigned int step,
                                        const double t) const
{
  if (signal != 0)
    AssertThrow(false, ExcInterrupted(interrupt::name(signal), step, t));
}

template <int dim>
void RunGuard<dim>::stop_if_any(const std::size_t p, const unsigned int step,
                                const double t,
                                const std::function<std::string(std::size_t)> &why) const
{
  const auto stop = [&]()
  {
    AssertThrow(false, ExcRunAborted(step, t, particles.id[p],
                                     point_to_string(particles.position[p]), why(p)));
  };
  if (!ranks.distributed())
  {
    if (p < particles.size())
      stop();
    return;
  }
  constexpr unsigned long long none = ~0ull;
  const unsigned long long mine     = p < particles.size() ? particles.id[p] : none;
  const unsigned long long lowest   = ranks.min(mine);
  if (lowest == none)
    return;
  // The rank holding the particle words the diagnostic; every rank stops with it.
  std::string message;
  if (mine == lowest)
    try
    {
      stop();
    }
    catch (const ExcRunAborted &e)
    {
      message = input::concise_message(e);
    }
  const auto holder = static_cast<unsigned int>(
      ranks.min(mine == lowest ? ranks.rank() : ranks.n_ranks()));
  AssertThrow(false, ExcRunStopped(ranks.broadcast(message, holder)));
}

template class RunGuard<2>;
template class RunGuard<3>;
} // namespace lme_mpm
