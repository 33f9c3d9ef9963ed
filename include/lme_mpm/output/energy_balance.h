#ifndef LME_MPM_OUTPUT_ENERGY_BALANCE_H
#define LME_MPM_OUTPUT_ENERGY_BALANCE_H

#include <lme_mpm/materials/material_set.h>
#include <lme_mpm/particles/particle_store.h>

#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace lme_mpm
{
/// The energies of the particles at one time (J).
struct Energies
{
  double kinetic = 0, strain = 0, dissipated = 0, external_work = 0;
  /// Kinetic + strain + dissipated energy minus the work of external forces.
  double total() const { return kinetic + strain + dissipated - external_work; }
  std::map<std::string, double> as_map() const;
};

/**
 * The energy balance of a run: the work of external forces (reactions and body
 * forces) added step by step, and the largest drift of the total energy from its
 * initial value over the output times, relative to the largest energy in play (so a
 * body starting at rest is measured too).
 */
template <int dim>
class EnergyBalance
{
public:
  void add_external_work(const double w) { external_work += w; }
  /// Bodies (flag per body index) left out of the kinetic energy: those that move as
  /// prescribed, whose motion is input (their work on the others is external work).
  void set_excluded_bodies(const std::vector<std::uint8_t> &flags) { excluded = flags; }
  /// The energies now; sums independent of the thread count.
  Energies measure(const ParticleStore<dim> &particles,
                   const MaterialSet<dim> &materials) const;
  /// Updates the drift with the energies of an output time; @p initial sets the
  /// reference total.
  void record(const Energies &e, bool initial);
  double max_drift() const { return max_energy_drift; }

  /// history.csv columns.
  static void write_header(std::ostream &out);
  static void write_row(std::ostream &out, const Energies &e);

  template <class Archive>
  void serialize(Archive &ar)
  {
    ar(external_work, initial_total_energy, energy_scale, max_energy_drift);
  }

private:
  std::vector<std::uint8_t> excluded;
  double external_work = 0, initial_total_energy = 0, energy_scale = 0,
         max_energy_drift = 0;
};
} // namespace lme_mpm

#endif
