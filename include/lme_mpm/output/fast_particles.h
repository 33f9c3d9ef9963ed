#ifndef LME_MPM_OUTPUT_FAST_PARTICLES_H
#define LME_MPM_OUTPUT_FAST_PARTICLES_H

#include <lme_mpm/base/archive.h>
#include <lme_mpm/particles/particle_store.h>

#include <cstdint>
#include <vector>

#include <ostream>
#include <string>

namespace lme_mpm
{
/**
 * How fast the particles cross cells, against the body's own dynamics: the distance in
 * cells that the fastest particle covers while a P-wave crosses the largest body,
 * `M = max_p |v_p| D / (c_P h_min)` (D the diagonal of the largest body's bounding box
 * at the start). Shape functions whose gradient jumps at cell faces (linear) or whose
 * particle boxes do not follow the strain (uGIMP) exchange energy with the particles at
 * every crossing, and no time step removes it; B-splines and LME do not. The level at
 * which each family was measured to drift by more than 1 % (the vibrating bar,
 * doc/stability.md) is the warning's: passing it prints one warning and lists it in
 * summary.json.
 */
class FastParticles
{
public:
  /// For shape functions @p family on a grid of smallest spacing @p h_min, the
  /// fastest P-wave speed @p c_P and the largest body's diagonal @p transit_length.
  void set_up(const std::string &family, double h_min, double c_P, double transit_length);
  /// The diagonal of the largest bounding box of the bodies in @p particles that are
  /// not prescribed (@p prescribed per body, nonzero for a prescribed one): the length
  /// a P-wave crosses.
  template <int dim>
  static double transit_length(const ParticleStore<dim> &particles,
                               const std::vector<std::uint8_t> &prescribed);
  /// After each step with the fastest particle's speed; true the first time the
  /// family's level is passed (the caller prints warning()).
  bool observe(double max_speed);
  /// The largest M since the previous row (history column `fast_particle_cells`).
  void write_header(std::ostream &out) const;
  void write_row(std::ostream &out);
  /// The largest M of the run.
  double max() const { return run_max; }
  /// The warning's text once the level has been passed, "" otherwise.
  std::string warning() const;
  /// The level of M above which @p family was measured to drift by more than 1 %
  /// (infinite for the families that do not warn).
  static double warning_level(const std::string &family);

  void serialize(Archive &ar) { ar(row_max, run_max, passed_at); }

private:
  std::string family;
  double cells_per_speed = 0, level = 0;
  double row_max = 0, run_max = 0;
  /// M when the level was first passed (0 before).
  double passed_at = 0;
};
} // namespace lme_mpm

#endif
