#include <deal.II/base/data_out_base.h>

#include <lme_mpm/base/tensor_tools.h>
#include <lme_mpm/output/particle_output.h>

namespace lme_mpm
{
template <int dim>
ParticleOutput<dim>::ParticleOutput(const std::string &directory)
    : particle_files(directory, "particles")
{
}

template <int dim>
void ParticleOutput<dim>::write(const ParticleStore<dim> &particles, const double time)
{
  const std::size_t n = particles.size();
  // Vectors first, then scalars: the effective stress (what the forces use) and the
  // undamaged one, the max principal effective stress, damage, ids.
  std::vector<std::string> names;
  std::vector<std::tuple<unsigned int, unsigned int, std::string,
                         DataComponentInterpretation::DataComponentInterpretation>>
      vectors;
  for (const char *v : {"displacement", "velocity"})
  {
    vectors.emplace_back(names.size(), names.size() + dim - 1, v,
                         DataComponentInterpretation::component_is_part_of_vector);
    for (unsigned int d = 0; d < dim; ++d)
      names.push_back(v);
  }
  const char *comp[3] = {"x", "y", "z"};
  for (const char *stress : {"stress_", "undamaged_stress_"})
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = i; j < dim; ++j)
        names.push_back(std::string(stress) + comp[i] + comp[j]);
  for (const char *s : {"max_principal_stress", "damage", "failed", "onset_strain",
                        "material_id", "body_id", "particle_id", "density"})
    names.push_back(s);

  std::vector<DataOutBase::Patch<0, dim>> patches(n);
  for (std::size_t p = 0; p < n; ++p)
  {
    auto &patch       = patches[p];
    patch.vertices[0] = particles.position[p];
    patch.patch_index = p;
    patch.data.reinit(names.size(), 1);
    unsigned int k = 0;
    for (unsigned int d = 0; d < dim; ++d)
      patch.data(k++, 0) = particles.position[p][d] - particles.reference_position[p][d];
    for (unsigned int d = 0; d < dim; ++d)
      patch.data(k++, 0) = particles.velocity[p][d];
    const SymmetricTensor<2, dim> stress = effective_stress(particles, p);
    for (const auto *s : {&stress, &particles.stress[p]})
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = i; j < dim; ++j)
          patch.data(k++, 0) = (*s)[i][j];
    patch.data(k++, 0) = max_principal(stress);
    patch.data(k++, 0) = particles.damage[p];
    patch.data(k++, 0) = particles.failed[p];
    patch.data(k++, 0) = particles.onset_strain[p];
    patch.data(k++, 0) = particles.material_id[p];
    patch.data(k++, 0) = particles.body_id[p];
    patch.data(k++, 0) = particles.id[p];
    patch.data(k++, 0) = particles.density[p];
  }

  DataOutBase::VtkFlags flags(time);
  flags.compression_level = DataOutBase::VtkFlags::best_speed;
  particle_files.add(time, [&](std::ostream &out)
                     { DataOutBase::write_vtu(patches, names, vectors, flags, out); });
}

template class ParticleOutput<2>;
template class ParticleOutput<3>;
} // namespace lme_mpm
