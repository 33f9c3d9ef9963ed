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
/// A point where history.csv reports the effective stress averaged over nearby
/// particles.
template <int dim>
struct Probe
{
  std::string name;
  Point<dim> point;
  double radius;
};

/**
 * The probes of "Output/Probe N": history.csv columns probe_<name>_sxx, ... with
 * the volume-weighted mean effective stress (effective_stress(): (1 - damage) sigma,
 * zero for failed particles) of the particles within each probe's radius.
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
