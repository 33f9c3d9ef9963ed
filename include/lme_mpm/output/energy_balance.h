#ifndef LME_MPM_OUTPUT_ENERGY_BALANCE_H
#define LME_MPM_OUTPUT_ENERGY_BALANCE_H

#include <lme_mpm/base/archive.h>
#include <lme_mpm/base/rank_reductions.h>
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
  /// The energy in play: the largest of kinetic + strain + dissipated energy and the
  /// external work's magnitude.
  double in_play() const;
  std::map<std::string, double> as_map() const;
};

/**
 * The energy balance of a run: the work of external forces (reactions, body forces,
 * prescribed bodies' contact) added step by step, and the drift of the total energy
 * from its value at step 0, checked after every step. The drift is measured against
 * the run's energy scale, the largest energy in play over the run (and the initial
 * total's magnitude): max_drift() = max_t |E(t) - E(0)| / max_t scale(t). Both
 * maxima run over the same steps, so round-off in the first steps, when almost no
 * energy is in play, cannot dominate it (doc/outputs.md).
 */
template <int dim>
class EnergyBalance
{
public:
  void add_external_work(const double w) { external_work += w; }
  /// Bodies (flag per body index) left out of the kinetic energy: those that move as
  /// prescribed, whose motion is input (their work on the others is external work).
  void set_excluded_bodies(const std::vector<std::uint8_t> &flags) { excluded = flags; }
  /// The energies of the particles of @p particles that are this rank's own (not
  /// ghosts); sums independent of the thread count.
  Energies measure(const ParticleStore<dim> &particles,
                   const MaterialSet<dim> &materials) const;
  /// The same summed over the ranks (every rank calls it).
  Energies measure(const ParticleStore<dim> &particles, const MaterialSet<dim> &materials,
                   const RankReductions &ranks) const;
  /// Updates the drift with the energies @p e of a step; @p initial sets the
  /// reference total (step 0).
  void track(const Energies &e, bool initial);
  /// The largest drift so far over the largest energy in play so far.
  double max_drift() const { return max_abs_drift / std::max(energy_scale, 1e-300); }
  /// The largest |E(t) - E(0)| so far (J).
  double max_absolute_drift() const { return max_abs_drift; }
  /// The largest energy in play so far (J).
  double scale() const { return energy_scale; }

  /// history.csv columns.
  static void write_header(std::ostream &out);
  static void write_row(std::ostream &out, const Energies &e);

  void serialize(Archive &ar)
  {
    ar(external_work, initial_total_energy, energy_scale, max_abs_drift);
  }

private:
  std::vector<std::uint8_t> excluded;
  double external_work = 0, initial_total_energy = 0, energy_scale = 0, max_abs_drift = 0;
};
} // namespace lme_mpm

#endif
