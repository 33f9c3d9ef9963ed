#ifndef LME_MPM_MATERIALS_MATERIAL_H
#define LME_MPM_MATERIALS_MATERIAL_H

#include <deal.II/base/parameter_handler.h>

#include <lme_mpm/base/input.h>
#include <lme_mpm/base/registry.h>
#include <lme_mpm/particles/particle_store.h>

#include <string>
#include <vector>

namespace lme_mpm
{
/// How a 2D model reads the third direction.
enum class PlaneAssumption
{
  plane_strain,
  plane_stress
};

/// What a material needs to know about the problem.
struct MaterialContext
{
  unsigned int dim      = 2;
  PlaneAssumption plane = PlaneAssumption::plane_strain;
  /// Reference density (kg/m^3), an entry every material shares.
  double density = 1.0;
  /// "Material N/<model>", for error messages naming the entry.
  std::string section = "Material";
};

/**
 * A constitutive model. It advances the stress of a range of particles from their
 * strain increment in one call (no virtual call per particle) and reports what the
 * time step and the energy balance need.
 */
template <int dim>
class Material
{
public:
  virtual ~Material() = default;

  virtual std::string name() const = 0;

  /// Mass density of the reference configuration (kg/m^3).
  virtual double density() const = 0;

  /// Fastest elastic wave speed at the reference density (m/s), for the time step.
  virtual double wave_speed() const = 0;

  /**
   * The model's entries that set wave_speed(), with their values and physical ranges
   * (the density is the material set's): messages about the time step name them. A
   * model that lists none is named by its subsection.
   */
  virtual std::vector<input::EntryValue> wave_speed_inputs() const { return {}; }

  /**
   * Updates `stress` (and any internal state) of the particles in [begin, end) that
   * carry material id @p material_id, from `strain_increment`.
   */
  virtual void update_stress(ParticleStore<dim> &particles, std::size_t begin,
                             std::size_t end, unsigned int material_id) const = 0;

  /// Elastic energy (J) stored in the particles of [begin, end) with this material.
  virtual double strain_energy(const ParticleStore<dim> &particles, std::size_t begin,
                               std::size_t end, unsigned int material_id) const = 0;
};

template <int dim>
using MaterialRegistry = Registry<Material<dim>, MaterialContext>;
} // namespace lme_mpm

/**
 * Registers material class template CLASS (templated on dim, constructed from
 * (ParameterHandler &, const MaterialContext &), with a static
 * declare_parameters(ParameterHandler &)) under NAME for dim = 2 and 3. Its entries
 * are declared in the subsection "Material N/NAME".
 */
#define LME_MPM_REGISTER_MATERIAL(CLASS, NAME, DESCRIPTION)                              \
  LME_MPM_REGISTER_PLUGIN_FOR_DIMS(::lme_mpm::MaterialRegistry, material, CLASS, NAME,   \
                                   DESCRIPTION,                                          \
                                   ::lme_mpm::PluginEntries::own_subsection)

#endif
