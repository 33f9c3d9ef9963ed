#ifndef LME_MPM_OUTPUT_PARTICLE_OUTPUT_H
#define LME_MPM_OUTPUT_PARTICLE_OUTPUT_H

#include <lme_mpm/output/vtu_series.h>
#include <lme_mpm/particles/particle_store.h>

#include <string>
#include <vector>

namespace lme_mpm
{
/**
 * Writes the particles as a VTU point cloud per output time and keeps the PVD record
 * of the series current, so that a run that stops early leaves a readable series.
 */
template <int dim>
class ParticleOutput
{
public:
  using Records = VtuSeries::Records;

  explicit ParticleOutput(const std::string &directory);

  /**
   * Writes particles_<index>.vtu and updates particles.pvd. The fields "stress_*" and
   * "max_principal_stress" are of the effective stress (effective_stress(), what the
   * forces use: (1 - damage) sigma, 0 once failed); "undamaged_stress_*" is sigma.
   */
  void write(const ParticleStore<dim> &particles, double time);

  /// The series written so far (for checkpoints), and its restoration on resume.
  const Records &series() const { return particle_files.records(); }
  void restore(const Records &records) { particle_files.restore(records); }

private:
  VtuSeries particle_files;
};
} // namespace lme_mpm

#endif
