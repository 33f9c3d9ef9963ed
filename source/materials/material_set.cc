#include <lme_mpm/base/format.h>
#include <lme_mpm/base/input.h>
#include <lme_mpm/base/parameters.h>
#include <lme_mpm/materials/material_set.h>

#include <algorithm>
#include <cmath>
#include <limits>

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
                                        const bool plane_stress, const bool si_units)
{
  MaterialContext context;
  context.dim = dim;
  context.plane =
      plane_stress ? PlaneAssumption::plane_stress : PlaneAssumption::plane_strain;
  EntryList list(prm, EntryList::Mode::parse);
  models.clear();
  warnings.clear();
  ranges_apply = si_units;
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
    const auto inputs = inputs_of(m);
    for (const auto &v : inputs)
      if (!v.physical())
        warnings.push_back(v.describe() + ": the run goes on, but check the value");
    const double c = models.back()->wave_speed();
    AssertThrow(std::isfinite(c) && c > 0,
                ExcBadInput(inputs.front().entry,
                            input::describe_entries(inputs) +
                                " give the P-wave speed c_P = " + format_double(c) +
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
std::vector<input::EntryValue> MaterialSet<dim>::inputs_of(const unsigned int m) const
{
  const std::string section             = input::subsection_name("Material", m);
  std::vector<input::EntryValue> inputs = models[m]->wave_speed_inputs();
  if (inputs.empty()) // a plug-in that lists none: its subsection stands for them
    inputs.push_back({section + "/" + models[m]->name(),
                      std::numeric_limits<double>::quiet_NaN(), "", 0, 0});
  inputs.insert(inputs.begin() + (inputs.size() > 1 ? 1 : 0),
                {section + "/Density", models[m]->density(), "kg/m^3", 1, 1e5});
  if (!ranges_apply) // a unitless problem: no value is out of range
    for (auto &v : inputs)
    {
      v.low  = -std::numeric_limits<double>::infinity();
      v.high = std::numeric_limits<double>::infinity();
    }
  return input::unphysical_first(inputs);
}

template <int dim>
std::vector<input::EntryValue> MaterialSet<dim>::wave_speed_inputs() const
{
  unsigned int fastest = 0;
  for (unsigned int m = 0; m < models.size(); ++m)
    if (!(models[m]->wave_speed() <= models[fastest]->wave_speed()))
      fastest = m;
  return models.empty() ? std::vector<input::EntryValue>{} : inputs_of(fastest);
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
