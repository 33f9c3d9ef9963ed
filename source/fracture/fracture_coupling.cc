#include <deal.II/base/symmetric_tensor.h>

#include <lme_mpm/base/input.h>
#include <lme_mpm/base/parallel.h>
#include <lme_mpm/base/tensor_tools.h>
#include <lme_mpm/fracture/fracture_coupling.h>

#include <cmath>

namespace lme_mpm
{
template <int dim>
void FractureCoupling<dim>::declare_parameters(ParameterHandler &prm,
                                               const unsigned int n_materials)
{
  for (unsigned int m = 0; m < n_materials; ++m)
  {
    prm.enter_subsection(input::subsection_name("Material", m));
    prm.enter_subsection("Fracture");
    declare_fracture_parameters<dim>(prm);
    prm.leave_subsection();
    prm.leave_subsection();
  }
}

template <int dim>
void FractureCoupling<dim>::parse_parameters(ParameterHandler &prm,
                                             const MaterialSet<dim> &materials,
                                             const double grid_spacing,
                                             const double thickness)
{
  models.clear();
  any_model = false;
  for (unsigned int m = 0; m < materials.size(); ++m)
  {
    const std::string section = input::subsection_name("Material", m);
    prm.enter_subsection(section);
    prm.enter_subsection("Fracture");
    const std::string model = prm.get("Model");
    if (model != "none")
    {
      FractureContext fc;
      fc.grid_spacing   = grid_spacing;
      fc.thickness      = thickness;
      fc.dim            = dim;
      fc.p_wave_modulus = materials[m].density() * std::pow(materials[m].wave_speed(), 2);
      fc.section        = section + "/Fracture";
      models.push_back(FractureModelRegistry<dim>::instance().create(model, prm, fc));
      any_model = true;
    }
    else
      models.emplace_back();
    prm.leave_subsection();
    prm.leave_subsection();
  }
}

template <int dim>
void FractureCoupling<dim>::check_neighbourhood(const unsigned int material,
                                                const double spacing, const double h_min,
                                                const std::string &body_section) const
{
  if (!models[material])
    return;
  AssertThrow(models[material]->epsilon() >= spacing,
              ExcBadInput(input::subsection_name("Material", material) +
                              "/Fracture/Epsilon factor",
                          "the neighbourhood radius C_eps h = " +
                              std::to_string(models[material]->epsilon()) +
                              " is smaller than the particle spacing " +
                              std::to_string(spacing) + " of " + body_section +
                              "; raise it to at least " +
                              std::to_string(spacing / h_min)));
}

template <int dim>
void FractureCoupling<dim>::update(ParticleStore<dim> &store)
{
  const std::size_t n = store.size();
  double radius       = 0;
  for (const auto &f : models)
    if (f)
      radius = std::max(radius, f->epsilon());
  // Neighbours from the particle's own body only: a tool pressed against a specimen
  // must not enter its onset or energy averages.
  neighbours.build(store.position, radius, &store.body_id);
  // Snapshot of what neighbours read, so that no update sees another's new state.
  fields.max_principal_stress.resize(n);
  fields.energy_density.resize(n);
  parallel::for_range(
      n,
      [&](const std::size_t b, const std::size_t e)
      {
        for (std::size_t p = b; p < e; ++p)
        {
          const bool alive               = !store.failed[p];
          fields.max_principal_stress[p] = alive ? eigenvalues(store.stress[p])[0] : 0.0;
          fields.energy_density[p] =
              alive ? 0.5 * (1 - store.damage[p]) * (store.stress[p] * store.strain[p])
                    : 0.0;
        }
      });
  parallel::for_range(n,
                      [&](const std::size_t b, const std::size_t e)
                      {
                        for (unsigned int m = 0; m < models.size(); ++m)
                          if (models[m])
                            models[m]->update(store, neighbours, fields, b, e, m);
                      });
}

template <int dim>
void FractureCoupling<dim>::add_statistics(const ParticleStore<dim> &store,
                                           std::map<std::string, double> &results) const
{
  for (const auto &f : models)
    if (f)
      for (const auto &s : f->statistics())
        results[f->name() + "_" + s.first] = s.second;
  if (!any_model)
    return;
  std::size_t failed = 0;
  for (const auto f : store.failed)
    failed += f;
  results["failed_particles"] = failed;
}

template class FractureCoupling<2>;
template class FractureCoupling<3>;
} // namespace lme_mpm
