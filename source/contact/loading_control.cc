#include <lme_mpm/base/format.h>
#include <lme_mpm/base/input.h>
#include <lme_mpm/contact/loading_control.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace lme_mpm
{
namespace
{
/// The gain a servo assumes before the opening has answered the travel: small, so
/// that the device starts at its full stroke.
constexpr double gain_floor = 1e-6;
/// The default response time in P-wave transits across the specimen: slow enough
/// that the loop does not ring with the waves, fast enough to follow a softening
/// branch (doc/loading_control.md: 5 held a notched beam's rate within 5.5 %, 20
/// within 38 %).
constexpr double transits = 5;
} // namespace

template <int dim>
void LoadingControl<dim>::declare_parameters(ParameterHandler &prm)
{
  prm.enter_subsection("Loading control");
  prm.declare_entry(
      "Type", "constant velocity", Patterns::Selection("constant velocity|opening rate"),
      "'constant velocity': the loading devices move as their Prescribed velocity "
      "says (the paper's loading). 'opening rate': a servo scales their velocity by "
      "a factor in [-1, 1] so that the opening gauge 'Gauge' grows at 'Opening "
      "rate' (doc/loading_control.md); the prescribed velocity is the fastest stroke.");
  prm.declare_entry("Gauge", "", Patterns::Anything(),
                    "The name of the 'Output/Opening gauges' gauge the servo holds to "
                    "its rate (opening rate only).");
  prm.declare_entry("Opening rate", "0", Patterns::Double(0),
                    "The rate at which the servo makes the gauge open (m/s), > 0 "
                    "(opening rate only).");
  prm.declare_entry("Devices", "", Patterns::Anything(),
                    "The names of the bodies the servo moves, comma separated: bodies "
                    "with a Prescribed velocity (rollers, platens).");
  prm.declare_entry("Response time", "0", Patterns::Double(0),
                    "The time in which the servo closes a lag of the opening behind "
                    "its target (s); 0: 5 transit times of the P wave across the "
                    "bounding box of the gauged bodies.");
  prm.leave_subsection();
}

template <int dim>
void LoadingControl<dim>::parse_parameters(ParameterHandler &prm, Bodies<dim> &controlled,
                                           const OpeningGauges<dim> &g)
{
  bodies = &controlled;
  prm.enter_subsection("Loading control");
  on                            = prm.get("Type") == "opening rate";
  const std::string gauge_name  = input::trim(prm.get("Gauge"));
  rate                          = prm.get_double("Opening rate");
  const std::string device_list = prm.get("Devices");
  response_time                 = prm.get_double("Response time");
  prm.leave_subsection();
  gauges = &g;
  devices.clear();
  for (const std::string &name : input::split(device_list, ','))
  {
    unsigned int b = 0;
    while (b < bodies->size() && bodies->name(b) != name)
      ++b;
    AssertThrow(b < bodies->size(), ExcBadInput("Loading control/Devices",
                                                "no body is named '" + name + "'"));
    AssertThrow(bodies->prescribed(b),
                ExcBadInput("Loading control/Devices",
                            "body '" + name +
                                "' has no Prescribed velocity: a device moves as "
                                "prescribed, scaled by the servo"));
    devices.push_back(b);
  }
  if (!on)
    return;
  gauge = g.find(gauge_name);
  AssertThrow(
      gauge < g.size(),
      ExcBadInput(
          "Loading control/Gauge",
          "'" + gauge_name + "' is not a gauge of 'Output/Opening gauges'" +
              (g.empty() ? std::string(" (none is given)") : " (" + g.names() + ")")));
  AssertThrow(rate > 0, ExcBadInput("Loading control/Opening rate",
                                    "must be > 0 with Type = opening rate"));
  AssertThrow(!devices.empty(),
              ExcBadInput("Loading control/Devices",
                          "name at least one body with a Prescribed velocity"));
}

template <int dim>
void LoadingControl<dim>::set_up(const ParticleStore<dim> &p, const double wave_speed,
                                 const RankReductions *ranks)
{
  if (!on || response_time > 0)
    return;
  // The free bodies' bounding box (the gauged specimen; rollers and platens move as
  // prescribed and are left out).
  std::vector<double> hi(2 * dim, -std::numeric_limits<double>::max());
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.ghost[i] == 0 && !bodies->prescribed(p.body_id[i]))
      for (unsigned int d = 0; d < dim; ++d)
      {
        hi[d]       = std::max(hi[d], p.reference_position[i][d]);
        hi[dim + d] = std::max(hi[dim + d], -p.reference_position[i][d]);
      }
  double diagonal2 = 0;
  for (unsigned int d = 0; d < dim; ++d)
  {
    const double a = ranks ? ranks->max(hi[d]) : hi[d];
    const double b = ranks ? ranks->max(hi[dim + d]) : hi[dim + d];
    diagonal2 += (a + b) * (a + b);
  }
  response_time = transits * std::sqrt(diagonal2) / wave_speed;
}

template <int dim>
void LoadingControl<dim>::update(const ParticleStore<dim> &particles,
                                 const RankReductions *ranks, const double t,
                                 const double dt)
{
  if (!on)
    return;
  const double w = gauges->read(particles, ranks)[gauge];
  // The stroke the devices had over the step, at the speed factor they had.
  const double V_start = bodies->entry_velocity(devices[0], Point<dim>(), t - dt).norm();
  const double step_travel = lambda * V_start * dt;
  travel += step_travel;
  const double beta = std::exp(-dt / response_time);
  s_wt              = beta * s_wt + (w - opening) * step_travel;
  s_tt              = beta * s_tt + step_travel * step_travel;
  opening           = w;
  // The target, kept within reach so that a saturated device winds up no lag.
  target      = std::clamp(target + rate * dt, w - 2 * rate * response_time,
                           w + rate * response_time);
  double gain = gain_floor;
  if (travel > 0 && w > 0)
    gain = std::max(gain, w / travel);
  if (s_tt > 0)
    gain = std::max(gain, s_wt / s_tt);
  const double V       = bodies->entry_velocity(devices[0], Point<dim>(), t).norm();
  const double wanted  = rate + (target - w) / response_time;
  const double command = V > 0 ? std::clamp(wanted / (gain * V), -1.0, 1.0) : 1.0;
  // The device follows the command with a lag of a quarter of the response time:
  // the gauge rings with the specimen's waves, which the device would otherwise
  // follow and feed.
  lambda += (command - lambda) * (1 - std::exp(-4 * dt / response_time));
  velocity   = lambda * V;
  lambda_min = std::min(lambda_min, lambda);
  lambda_max = std::max(lambda_max, lambda);
  apply();
}

template <int dim>
void LoadingControl<dim>::apply() const
{
  for (const unsigned int b : devices)
    bodies->set_speed_factor(b, lambda);
}

template <int dim>
double LoadingControl<dim>::device_load(const std::vector<Tensor<1, dim>> &forces,
                                        const double t) const
{
  double load = 0;
  for (const unsigned int b : devices)
  {
    if (b >= forces.size())
      continue;
    const Tensor<1, dim> v = bodies->entry_velocity(b, Point<dim>(), t);
    // The specimen pushes a device back against its stroke.
    load += v.norm() > 0 ? -(forces[b] * v) / v.norm() : forces[b].norm();
  }
  return load;
}

template <int dim>
void LoadingControl<dim>::write_header(std::ostream &out) const
{
  if (on)
    out << ",control_target,device_travel,device_velocity";
}

template <int dim>
void LoadingControl<dim>::write_row(std::ostream &out) const
{
  if (on)
    out << "," << target << "," << travel << "," << velocity;
}

template <int dim>
void LoadingControl<dim>::add_results(std::map<std::string, double> &r) const
{
  if (!on)
    return;
  r["control_response_time"]    = response_time;
  r["control_device_travel"]    = travel;
  r["control_min_speed_factor"] = lambda_min;
  r["control_max_speed_factor"] = lambda_max;
}

template <int dim>
void LoadingControl<dim>::serialize(Archive &ar)
{
  ar(response_time, lambda, travel, target, opening, velocity, s_wt, s_tt);
  ar(lambda_min, lambda_max);
  if (ar.loading() && on)
    apply();
}

template class LoadingControl<2>;
template class LoadingControl<3>;
} // namespace lme_mpm
