#ifndef LME_MPM_FRACTURE_FRACTURE_COUPLING_H
#define LME_MPM_FRACTURE_FRACTURE_COUPLING_H

#include <deal.II/base/parameter_handler.h>

#include <lme_mpm/fracture/crack_set.h>
#include <lme_mpm/fracture/fracture_model.h>
#include <lme_mpm/fracture/neighbourhood.h>
#include <lme_mpm/grid/background_grid.h>
#include <lme_mpm/materials/material_set.h>
#include <lme_mpm/particles/particle_store.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace lme_mpm
{
/**
 * Couples the fracture models to the particles: one model (or none) per material,
 * read from "Material N/Fracture"; each step it rebuilds the epsilon-neighbourhood,
 * takes the snapshot of the fields neighbours read, and runs every model on its
 * material's particles. Runs after all stresses of the step are known.
 */
template <int dim>
class FractureCoupling
{
public:
  /// Declares "Material N/Fracture" for the @p n_materials materials.
  static void declare_parameters(ParameterHandler &prm, unsigned int n_materials);
  /**
   * Builds the models. The lengths tied to the grid (eps = C_eps h, a band width of 0)
   * use each particle's local spacing on @p grid (FractureFields::spacing); @p
   * thickness is the 2D thickness. The grid must outlive this object.
   */
  void parse_parameters(ParameterHandler &prm, const MaterialSet<dim> &materials,
                        const BackgroundGrid<dim> &grid, double thickness);

  /// True if any material fractures.
  bool active() const { return any_model; }
  bool fractures(const unsigned int material) const
  {
    return models[material] != nullptr;
  }
  /**
   * Throws unless the neighbourhood of @p material is at least as wide as the spacing
   * h / @p particles_per_cell of the particles @p body_section places, in the
   * smallest and the largest cells of the grid (a narrower one holds the particle
   * alone, and the criterion would average nothing).
   */
  void check_neighbourhood(unsigned int material, unsigned int particles_per_cell,
                           const std::string &body_section) const;

  /// The fracture update of one step, after the stresses. With @p cracks, particles
  /// on different faces of an explicit crack are not neighbours.
  void update(ParticleStore<dim> &particles, const CrackSet<dim> *cracks = nullptr);

  /// Counters of every model, and the failed particles and dissipated energy.
  void add_statistics(const ParticleStore<dim> &particles,
                      std::map<std::string, double> &results) const;

private:
  std::vector<std::unique_ptr<FractureModel<dim>>> models; ///< per material, or null
  bool any_model                  = false;
  const BackgroundGrid<dim> *grid = nullptr;
  bool uniform_grid               = true;
  Neighbourhood<dim> neighbours;
  CrackSegmentBins<dim> crack_bins;
  FractureFields fields;
};
} // namespace lme_mpm

#endif
