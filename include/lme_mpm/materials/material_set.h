#ifndef LME_MPM_MATERIALS_MATERIAL_SET_H
#define LME_MPM_MATERIALS_MATERIAL_SET_H

#include <deal.II/base/parameter_handler.h>

#include <lme_mpm/materials/material.h>

#include <memory>
#include <string>
#include <vector>

namespace lme_mpm
{
/**
 * The materials of a run, one per "Material N" subsection, indexed by the particles'
 * material id. Block-wise calls run every material over a range of particles, each
 * acting on its own particles only.
 */
template <int dim>
class MaterialSet
{
public:
  /// Declares "Material 1" ... "Material n": model, density and the models' entries.
  static void declare_parameters(ParameterHandler &prm, unsigned int n_materials);
  /// With @p si_units, an entry outside its physical range is named in
  /// input_warnings().
  void parse_parameters(ParameterHandler &prm, unsigned int n_materials,
                        bool plane_stress, bool si_units = true);

  unsigned int size() const { return models.size(); }
  const Material<dim> &operator[](const unsigned int m) const { return *models[m]; }
  /// The fastest P-wave speed of all materials (m/s).
  double max_wave_speed() const;
  /// The entries that set max_wave_speed() with their values, unphysical ones
  /// first, for messages.
  std::vector<input::EntryValue> wave_speed_inputs() const;
  /// One line per entry outside its physical range (the run goes on).
  const std::vector<std::string> &input_warnings() const { return warnings; }

  /// Updates the stress of [begin, end), one call per material.
  void update_stress(ParticleStore<dim> &particles, const std::size_t begin,
                     const std::size_t end) const
  {
    for (unsigned int m = 0; m < models.size(); ++m)
      models[m]->update_stress(particles, begin, end, m);
  }
  /// Elastic energy stored in [begin, end) (J).
  double strain_energy(const ParticleStore<dim> &particles, std::size_t begin,
                       std::size_t end) const;

private:
  /// Material @p m's density and model entries, unphysical first.
  std::vector<input::EntryValue> inputs_of(unsigned int m) const;

  std::vector<std::unique_ptr<Material<dim>>> models;
  std::vector<std::string> warnings;
  /// False for a unitless problem (Problem/Units).
  bool ranges_apply = true;
};
} // namespace lme_mpm

#endif
