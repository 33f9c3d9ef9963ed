#ifndef LME_MPM_OUTPUT_PARTICLE_OUTPUT_H
#define LME_MPM_OUTPUT_PARTICLE_OUTPUT_H

#include <deal.II/base/data_out_base.h>

#include <lme_mpm/output/vtu_series.h>
#include <lme_mpm/particles/particle_store.h>

#include <string>
#include <tuple>
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

  /// @p thickness: the real thickness of a 2D run (the field "size" is the side of a
  /// particle's area, volume / thickness); ignored in 3D.
  ParticleOutput(const std::string &directory, double thickness);

  /**
   * Writes particles_<index>.vtu and updates particles.pvd. The fields "stress_*" and
   * "max_principal_stress" are of the effective stress (effective_stress(), what the
   * forces use: (1 - damage) sigma, 0 once failed); "undamaged_stress_*" is sigma.
   */
  void write(const ParticleStore<dim> &particles, double time);
  /**
   * A distributed run's output: each of the @p n_ranks ranks writes its own
   * particles (not the ghosts) as a piece, rank 0 the .pvtu that joins them.
   */
  void write_piece(const ParticleStore<dim> &particles, double time, unsigned int rank,
                   unsigned int n_ranks);

  /// The series written so far (for checkpoints), and its restoration on resume.
  const Records &series() const { return particle_files.records(); }
  void restore(const Records &records) { particle_files.restore(records); }

private:
  /// The patches of the particles that are not ghosts, and the field names.
  void patches(
      const ParticleStore<dim> &particles,
      std::vector<DataOutBase::Patch<0, dim>> &patches, std::vector<std::string> &names,
      std::vector<std::tuple<unsigned int, unsigned int, std::string,
                             DataComponentInterpretation::DataComponentInterpretation>>
          &vectors) const;
  VtuSeries particle_files;
  double thickness;
};
} // namespace lme_mpm

#endif
