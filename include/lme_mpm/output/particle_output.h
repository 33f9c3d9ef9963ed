#ifndef LME_MPM_OUTPUT_PARTICLE_OUTPUT_H
#define LME_MPM_OUTPUT_PARTICLE_OUTPUT_H

#include <lme_mpm/grid/background_grid.h>
#include <lme_mpm/output/grid_output.h>
#include <lme_mpm/output/vtu_series.h>
#include <lme_mpm/particles/particle_store.h>

#include <string>
#include <vector>

namespace lme_mpm
{
/**
 * Writes the particles as a VTU point cloud per output time and keeps the PVD record
 * of the series current, so that a run that stops early leaves a readable series.
 *
 * The grid files are GridOutput's; write_grid(), grid_series() and the grid argument
 * of restore() only forward to the GridOutput this class owns, for a caller that
 * does not own one itself.
 */
template <int dim>
class ParticleOutput
{
public:
  using Records = VtuSeries::Records;

  /// @p write_grid: whether write_grid() writes the grid files.
  explicit ParticleOutput(const std::string &directory, bool write_grid = false);

  /// Writes particles_<index>.vtu and updates particles.pvd.
  void write(const ParticleStore<dim> &particles, double time);

  /// The series written so far (for checkpoints), and their restoration on resume.
  const Records &particle_series() const { return particle_files.records(); }
  void restore(const Records &particles, const Records &grid = {})
  {
    particle_files.restore(particles);
    grid_output.restore(grid);
  }

  /// GridOutput::write() if the grid files are enabled.
  void write_grid(const BackgroundGrid<dim> &grid, const std::vector<double> &nodal_mass,
                  const std::vector<Tensor<1, dim>> &nodal_velocity, double time)
  {
    if (grid_enabled)
      grid_output.write(grid, nodal_mass, nodal_velocity, time);
  }
  const Records &grid_series() const { return grid_output.series(); }

private:
  VtuSeries particle_files;
  GridOutput<dim> grid_output;
  bool grid_enabled;
};
} // namespace lme_mpm

#endif
