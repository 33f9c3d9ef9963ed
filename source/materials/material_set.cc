#include <lme_mpm/base/format.h>
#include <lme_mpm/base/input.h>
#include <lme_mpm/base/parameters.h>
#include <lme_mpm/materials/material_set.h>

#include <algorithm>
#include <cmath>

namespace lme_mpm
{
namespace
{
/// The entries every "Material N" has, listed once for declaring and reading.
template <int dim>
struct MaterialEntries
{
  std::string model;
  double density = 1000;

  void entries(EntryList &list)
  {
    const auto &registry = MaterialRegistry<dim>::instance();
    list.add("Model", model, "linear elastic", Patterns::Selection(registry.pattern()),
             "Constitutive model. " + registry.documentation());
    list.add("Density", density, "1000", Patterns::Double(0), "Density (kg/m^3), > 0.");
  }
};
} // namespace

template <int dim>
void MaterialSet<dim>::declare_parameters(ParameterHandler &prm,
                                          const unsigned int n_materials)
{
  EntryList list(prm, EntryList::Mode::declare);
  for (unsigned int m = 0; m < n_materials; ++m)
  {
    prm.enter_subsection(input::subsection_name("Material", m));
    MaterialEntries<dim>().entries(list);
    MaterialRegistry<dim>::instance().declare_all(prm);
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
  EntryList list(prm, EntryList::Mode::parse);
  models.clear();
  for (unsigned int m = 0; m < n_materials; ++m)
  {
    const std::string section = input::subsection_name("Material", m);
    prm.enter_subsection(section);
    MaterialEntries<dim> in;
    in.entries(list);
    context.density = in.density;
    context.section = section + "/" + in.model;
    input::require_range(context.density, 0, 1e300, true, section + "/Density");
    models.push_back(MaterialRegistry<dim>::instance().create(in.model, prm, context));
    // In range one by one, the entries may still give a useless wave speed (a huge
    // modulus over a tiny density), and with it the time step.
    const double c = models.back()->wave_speed();
    AssertThrow(std::isfinite(c) && c > 0,
                ExcBadInput(context.section + " with " + section + "/Density",
                            "they give the P-wave speed c_P = " + format_double(c) +
                                " m/s; it must be finite and positive"));
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
std::string MaterialSet<dim>::wave_speed_entries() const
{
  unsigned int fastest = 0;
  for (unsigned int m = 0; m < models.size(); ++m)
    if (!(models[m]->wave_speed() <= models[fastest]->wave_speed()))
      fastest = m;
  if (models.empty())
    return "the materials' entries";
  const std::string material = input::subsection_name("Material", fastest);
  return "'" + material + "/Density' and the entries of '" + material + "/" +
         models[fastest]->name() + "'";
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
