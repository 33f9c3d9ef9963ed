#ifndef LME_MPM_GEOMETRY_PARTICLE_GENERATOR_H
#define LME_MPM_GEOMETRY_PARTICLE_GENERATOR_H

#include <deal.II/base/parameter_handler.h>

#include <lme_mpm/grid/background_grid.h>
#include <lme_mpm/particles/particle_store.h>

#include <cstdint>
#include <string>
#include <vector>

namespace lme_mpm
{
/// Where the particles of one body came from.
struct BodyPlacement
{
  std::string section;                 ///< "Body N", for messages
  unsigned int material           = 0; ///< 0-based material index
  unsigned int particles_per_cell = 2; ///< per cell direction
  /// 0-based materials of the body's "Material zones"
  std::vector<unsigned int> zone_materials;
  /// Per grid cell: 1 where the body placed particles (their lengths follow it)
  std::vector<std::uint8_t> cells;
  /// Where the particles sit in a cell along each direction (fractions of the cell)
  std::vector<double> offsets;
  /// Their volume's share of the cell along each direction (sums to 1)
  std::vector<double> weights;
};

/**
 * Fills the bodies ("Body N": shape, holes, material, placement rule, particles per
 * cell direction, initial velocity) with particles at the Gauss points (or the
 * centres of equal sub-cells) of the background cells they cover.
 */
template <int dim>
class ParticleGenerator
{
public:
  static void declare_parameters(ParameterHandler &prm, unsigned int n_bodies);
  /**
   * Adds the particles of every body to @p particles and numbers them. The bodies'
   * materials must lie in [0, densities.size()), their densities (kg/m^3) set the
   * masses; @p thickness is the 2D thickness. Throws ExcBadInput naming the entry for
   * a body outside the grid or one that holds no particle.
   */
  static std::vector<BodyPlacement> fill(ParameterHandler &prm, unsigned int n_bodies,
                                         const BackgroundGrid<dim> &grid,
                                         const std::vector<double> &densities,
                                         double thickness, ParticleStore<dim> &particles);
};
} // namespace lme_mpm

#endif
