#include <deal.II/base/data_out_base.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/data_out.h>

#include <lme_mpm/base/tensor_tools.h>
#include <lme_mpm/output/particle_output.h>

#include <cstdio>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace lme_mpm
{
namespace
{
std::string numbered(const std::string &stem, const std::size_t i)
{
  std::ostringstream s;
  s << stem << "_" << std::setw(5) << std::setfill('0') << i << ".vtu";
  return s.str();
}

/// Writes to a temporary file and renames it, so a reader never sees half a file.
template <class F>
void write_atomically(const std::string &path, const F &write)
{
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    AssertThrow(out, ExcMessage("Cannot write '" + tmp + "'"));
    write(out);
  }
  AssertThrow(std::rename(tmp.c_str(), path.c_str()) == 0,
              ExcMessage("Cannot rename '" + tmp + "' to '" + path + "'"));
}
} // namespace

template <int dim>
ParticleOutput<dim>::ParticleOutput(const std::string &dir, const bool write_grid)
    : directory(dir), grid_enabled(write_grid)
{
}

template <int dim>
void ParticleOutput<dim>::write(const ParticleStore<dim> &particles, const double time)
{
  const std::size_t n = particles.size();
  // Scalars: stress components, max principal stress, damage, ids; vectors first.
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
  for (unsigned int i = 0; i < dim; ++i)
    for (unsigned int j = i; j < dim; ++j)
      names.push_back(std::string("stress_") + comp[i] + comp[j]);
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
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = i; j < dim; ++j)
        patch.data(k++, 0) = particles.stress[p][i][j];
    patch.data(k++, 0) = max_principal(particles.stress[p]);
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
  const std::string file  = numbered("particles", particle_records.size());
  write_atomically(directory + "/" + file, [&](std::ostream &out)
                   { DataOutBase::write_vtu(patches, names, vectors, flags, out); });
  particle_records.emplace_back(time, file);
  write_atomically(directory + "/particles.pvd", [&](std::ostream &out)
                   { DataOutBase::write_pvd_record(out, particle_records); });
}

template <int dim>
void ParticleOutput<dim>::write_grid(const BackgroundGrid<dim> &grid,
                                     const std::vector<double> &nodal_mass,
                                     const std::vector<Tensor<1, dim>> &nodal_velocity,
                                     const double time)
{
  if (!grid_enabled)
    return;
  Vector<double> velocity(grid.dof_handler().n_dofs()), mass(grid.dof_handler().n_dofs());
  for (unsigned int n = 0; n < grid.n_nodes(); ++n)
    for (unsigned int c = 0; c < dim; ++c)
    {
      velocity[grid.dof(n, c)] = nodal_velocity.empty() ? 0. : nodal_velocity[n][c];
      mass[grid.dof(n, c)]     = nodal_mass.empty() ? 0. : nodal_mass[n];
    }
  DataOut<dim> data_out;
  data_out.attach_dof_handler(grid.dof_handler());
  std::vector<DataComponentInterpretation::DataComponentInterpretation> vec(
      dim, DataComponentInterpretation::component_is_part_of_vector);
  data_out.add_data_vector(velocity, std::vector<std::string>(dim, "velocity"),
                           DataOut<dim>::type_dof_data, vec);
  data_out.add_data_vector(mass, std::vector<std::string>(dim, "nodal_mass"),
                           DataOut<dim>::type_dof_data, vec);
  data_out.build_patches();
  DataOutBase::VtkFlags flags(time);
  flags.compression_level = DataOutBase::VtkFlags::best_speed;
  data_out.set_flags(flags);
  const std::string file = numbered("grid", grid_records.size());
  write_atomically(directory + "/" + file,
                   [&](std::ostream &out) { data_out.write_vtu(out); });
  grid_records.emplace_back(time, file);
  write_atomically(directory + "/grid.pvd", [&](std::ostream &out)
                   { DataOutBase::write_pvd_record(out, grid_records); });
}

template class ParticleOutput<2>;
template class ParticleOutput<3>;
} // namespace lme_mpm
