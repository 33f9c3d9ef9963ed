#ifndef LME_MPM_OUTPUT_PARTICLE_OUTPUT_H
#define LME_MPM_OUTPUT_PARTICLE_OUTPUT_H

#include <lme_mpm/grid/background_grid.h>
#include <lme_mpm/particles/particle_store.h>

#include <string>
#include <utility>
#include <vector>

namespace lme_mpm
{
/**
 * Writes the particles as a VTU point cloud per output time and keeps the PVD record
 * of the series current, so that a run that stops early leaves a readable series.
 * Optional grid files carry the nodal velocity through deal.II's DataOut.
 */
template <int dim>
class ParticleOutput
{
public:
  ParticleOutput(const std::string &directory, bool write_grid);

  /// Writes particles_<index>.vtu and updates particles.pvd.
  void write(const ParticleStore<dim> &particles, double time);
  /// Writes grid_<index>.vtu with nodal velocity and mass (when enabled).
  void write_grid(const BackgroundGrid<dim> &grid, const std::vector<double> &nodal_mass,
                  const std::vector<Tensor<1, dim>> &nodal_velocity, double time);

  /// The series written so far (for checkpoints), and their restoration on resume.
  using Records = std::vector<std::pair<double, std::string>>;
  const Records &particle_series() const { return particle_records; }
  const Records &grid_series() const { return grid_records; }
  void restore(const Records &particles, const Records &grid)
  {
    particle_records = particles;
    grid_records     = grid;
  }

private:
  std::string directory;
  bool grid_enabled;
  std::vector<std::pair<double, std::string>> particle_records, grid_records;
};
} // namespace lme_mpm

#endif
