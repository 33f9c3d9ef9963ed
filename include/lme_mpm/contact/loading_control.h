#ifndef LME_MPM_CONTACT_LOADING_CONTROL_H
#define LME_MPM_CONTACT_LOADING_CONTROL_H

#include <deal.II/base/parameter_handler.h>

#include <lme_mpm/base/archive.h>
#include <lme_mpm/base/rank_reductions.h>
#include <lme_mpm/geometry/bodies.h>
#include <lme_mpm/output/gauges.h>
#include <lme_mpm/particles/particle_store.h>

#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace lme_mpm
{
/**
 * A servo-controlled press ("Loading control"): the loading devices (prescribed
 * bodies named in "Devices") move at lambda times their prescribed velocity, and
 * lambda in [-1, 1] follows from an opening gauge (OpeningGauges) so that the opening
 * w grows at the target rate r ("Opening rate"), as a laboratory keeps a crack mouth
 * opening or a lateral expansion growing at a constant rate after the peak. The
 * prescribed velocity is thereby the press's fastest stroke.
 *
 * The rule, evaluated after every step (doc/loading_control.md):
 *   lambda = clamp((r + e / T) / (g V), -1, 1),
 * with V the speed of the first device's prescribed velocity at the origin, e = w* -
 * w the opening's lag behind the target w* (w* grows by r dt and is kept within
 * [w - 2 r T, w + r T], so that a saturated device does not wind up a lag it would
 * later race to close), T the response time ("Response time", by default 5 transit
 * times of the P wave across the gauged bodies: slow against the specimen's ringing,
 * fast against the test) and g the gain dw/dtravel, estimated as the larger of the
 * secant w / travel and the tangent from the step increments, least squares with a
 * memory of T: overestimating g only slows the device. With g exact the lag obeys
 * de/dt = -e / T. The device follows lambda with a first-order lag of T / 4, so
 * that the ringing of the gauge with the specimen's waves does not drive it. The
 * device's acceleration from a change of lambda is not added
 * to the prescribed acceleration of multi-field contact.
 */
template <int dim>
class LoadingControl
{
public:
  static void declare_parameters(ParameterHandler &prm);
  /**
   * Reads the entries; throws ExcBadInput naming the entry for an unknown gauge or
   * device, a device that is not prescribed, or a rate that is not positive. Keeps
   * @p bodies to set the devices' speed factor.
   */
  void parse_parameters(ParameterHandler &prm, Bodies<dim> &bodies,
                        const OpeningGauges<dim> &gauges);
  /**
   * Sets the response time when the entry is 0: 5 times the P-wave transit time
   * across the bounding box of the free bodies' particles (@p wave_speed the fastest
   * material's), summed over @p ranks (null on one rank).
   */
  void set_up(const ParticleStore<dim> &particles, double wave_speed,
              const RankReductions *ranks);

  bool active() const { return on; }
  /// True if "Devices" names bodies (with either loading type).
  bool has_devices() const { return !devices.empty(); }
  /**
   * The devices' load: the contact forces @p forces (per body) they receive, against
   * their prescribed direction at @p t, summed (N; per unit thickness as the forces).
   */
  double device_load(const std::vector<Tensor<1, dim>> &forces, double t) const;
  /**
   * After a step of length @p dt that ends at @p t: reads the gauge (a collective
   * call), integrates the travel, and sets the devices' speed factor (Bodies) for
   * the next step.
   */
  void update(const ParticleStore<dim> &particles, const RankReductions *ranks, double t,
              double dt);

  void write_header(std::ostream &out) const;
  void write_row(std::ostream &out) const;
  void add_results(std::map<std::string, double> &results) const;
  void serialize(Archive &ar);

private:
  bool on            = false;
  unsigned int gauge = 0;
  std::vector<unsigned int> devices;
  double rate = 0, response_time = 0;
  const OpeningGauges<dim> *gauges = nullptr;
  Bodies<dim> *bodies              = nullptr;
  /// Gives the devices the speed factor.
  void apply() const;

  /// The device's speed factor lambda, travel, the target and the last reading.
  double lambda = 1, travel = 0, target = 0, opening = 0, velocity = 0;
  /// The tangent gain's weighted sums: increments of opening times travel, travel^2.
  double s_wt = 0, s_tt = 0;
  /// The largest and smallest speed factor set.
  double lambda_min = 1, lambda_max = -1;
};
} // namespace lme_mpm

#endif
