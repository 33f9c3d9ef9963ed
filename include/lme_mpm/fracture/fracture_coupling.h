#ifndef LME_MPM_FRACTURE_FRACTURE_COUPLING_H
#define LME_MPM_FRACTURE_FRACTURE_COUPLING_H

#include <deal.II/base/parameter_handler.h>

#include <lme_mpm/fracture/fracture_model.h>
#include <lme_mpm/fracture/neighbourhood.h>
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
   * Builds the models; @p grid_spacing is the h of eps = C_eps h, @p thickness the
   * 2D thickness.
   */
  void parse_parameters(ParameterHandler &prm, const MaterialSet<dim> &materials,
                        double grid_spacing, double thickness);

  /// True if any material fractures.
  bool active() const { return any_model; }
  bool fractures(const unsigned int material) const
  {
    return models[material] != nullptr;
  }
  /**
   * Throws unless the neighbourhood of @p material is at least as wide as the spacing
   * @p particle_spacing of the particles @p body_section places (a narrower one holds
   * the particle alone, and the criterion would average nothing); @p h_min turns the
   * spacing into the smallest accepted epsilon factor.
   */
  void check_neighbourhood(unsigned int material, double particle_spacing, double h_min,
                           const std::string &body_section) const;

  /// The fracture update of one step, after the stresses.
  void update(ParticleStore<dim> &particles);

  /// Counters of every model, and the failed particles and dissipated energy.
  void add_statistics(const ParticleStore<dim> &particles,
                      std::map<std::string, double> &results) const;

private:
  std::vector<std::unique_ptr<FractureModel<dim>>> models; ///< per material, or null
  bool any_model = false;
  Neighbourhood<dim> neighbours;
  FractureFields fields;
};
} // namespace lme_mpm

#endif
