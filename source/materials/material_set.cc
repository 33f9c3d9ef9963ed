#include <lme_mpm/base/input.h>
#include <lme_mpm/materials/material_set.h>

#include <algorithm>

namespace lme_mpm
{
template <int dim>
void MaterialSet<dim>::declare_parameters(ParameterHandler &prm,
                                          const unsigned int n_materials)
{
  const auto &registry = MaterialRegistry<dim>::instance();
  for (unsigned int m = 0; m < n_materials; ++m)
  {
    prm.enter_subsection(input::subsection_name("Material", m));
    prm.declare_entry("Model", "linear elastic", Patterns::Selection(registry.pattern()),
                      "Constitutive model. " + registry.documentation());
    prm.declare_entry("Density", "1000", Patterns::Double(0), "Density (kg/m^3), > 0.");
    registry.declare_all(prm);
    prm.leave_subsection();
  }
}

template <int dim>
void MaterialSet<dim>::parse_parameters(ParameterHandler &prm,
                                        const unsigned int n_materials,
                                        const bool plane_stress)
{
  MaterialContext context;
  context.dim = dim;
  context.plane =
      plane_stress ? PlaneAssumption::plane_stress : PlaneAssumption::plane_strain;
  models.clear();
  for (unsigned int m = 0; m < n_materials; ++m)
  {
    const std::string section = input::subsection_name("Material", m);
    prm.enter_subsection(section);
    const std::string model = prm.get("Model");
    context.density         = prm.get_double("Density");
    context.section         = section + "/" + model;
    input::require_range(context.density, 0, 1e300, true, section + "/Density");
    models.push_back(MaterialRegistry<dim>::instance().create(model, prm, context));
    prm.leave_subsection();
  }
}

template <int dim>
double MaterialSet<dim>::max_wave_speed() const
{
  double c_max = 0;
  for (const auto &m : models)
    c_max = std::max(c_max, m->wave_speed());
  return c_max;
}

template <int dim>
double MaterialSet<dim>::strain_energy(const ParticleStore<dim> &particles,
                                       const std::size_t begin,
                                       const std::size_t end) const
{
  double s = 0;
  for (unsigned int m = 0; m < models.size(); ++m)
    s += models[m]->strain_energy(particles, begin, end, m);
  return s;
}

template class MaterialSet<2>;
template class MaterialSet<3>;
} // namespace lme_mpm
