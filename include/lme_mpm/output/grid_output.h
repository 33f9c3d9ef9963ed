#ifndef LME_MPM_OUTPUT_GRID_OUTPUT_H
#define LME_MPM_OUTPUT_GRID_OUTPUT_H

#include <lme_mpm/grid/background_grid.h>
#include <lme_mpm/output/vtu_series.h>

#include <string>
#include <vector>

namespace lme_mpm
{
/**
 * Writes the background grid with the nodal velocity and mass through deal.II's
 * DataOut, one grid_<index>.vtu per output time, and keeps grid.pvd current.
 */
template <int dim>
class GridOutput
{
public:
  using Records = VtuSeries::Records;

  explicit GridOutput(const std::string &directory);

  /// Writes grid_<index>.vtu (zero where a field is empty) and updates grid.pvd.
  void write(const BackgroundGrid<dim> &grid, const std::vector<double> &nodal_mass,
             const std::vector<Tensor<1, dim>> &nodal_velocity, double time);

  /// The series written so far (for checkpoints), and its restoration on resume.
  const Records &series() const { return files.records(); }
  void restore(const Records &records) { files.restore(records); }

private:
  VtuSeries files;
};
} // namespace lme_mpm

#endif
