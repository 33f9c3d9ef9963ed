#ifndef LME_MPM_OUTPUT_PROBES_H
#define LME_MPM_OUTPUT_PROBES_H

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <lme_mpm/particles/particle_store.h>

#include <ostream>
#include <string>
#include <vector>

namespace lme_mpm
{
/// A point where history.csv reports means over the particles near it.
template <int dim>
struct Probe
{
  std::string name;
  Point<dim> point;
  double radius;
  /// Which means: the effective stress, displacement, velocity, damage.
  bool stress = true, displacement = false, velocity = false, damage = false;
};

/**
 * The probes of "Output/Probe N": history.csv columns, for the particles within each
 * probe's radius of its point, of the volume-weighted mean effective stress
 * (effective_stress(): (1 - damage) sigma, zero for failed particles) probe_<name>_sxx,
 * ..., the mass-weighted mean displacement probe_<name>_ux, ... and velocity
 * probe_<name>_vx, ..., and the volume-weighted mean damage probe_<name>_damage, as
 * the probe's 'Quantities' ask.
 */
template <int dim>
class Probes
{
public:
  /// Declares "Output/Probe 1" ... "Output/Probe n".
  static void declare_parameters(ParameterHandler &prm, unsigned int n_probes);
  /// Reads the @p n_probes probes.
  void parse_parameters(ParameterHandler &prm, unsigned int n_probes);

  /// The probes' columns of the history header, each preceded by a comma.
  void write_header(std::ostream &out) const;
  /// The probes' mean effective stresses of one history row, each after a comma.
  void write_row(std::ostream &out, const ParticleStore<dim> &particles) const;

private:
  std::vector<Probe<dim>> probes;
};
} // namespace lme_mpm

#endif
