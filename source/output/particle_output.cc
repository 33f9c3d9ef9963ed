#include <deal.II/base/data_out_base.h>

#include <lme_mpm/base/tensor_tools.h>
#include <lme_mpm/output/particle_output.h>
#include <lme_mpm/particles/damage_form.h>

#include <cmath>
#include <limits>

namespace lme_mpm
{
namespace
{
/// The largest principal value for output, NaN for a state that is not finite (a run
/// that went unstable still writes its last state).
template <int dim>
double largest_principal(const SymmetricTensor<2, dim> &s)
{
  return std::isfinite(s.norm()) ? max_principal(s)
                                 : std::numeric_limits<double>::quiet_NaN();
}
} // namespace

template <int dim>
ParticleOutput<dim>::ParticleOutput(const std::string &directory, const double thickness)
    : particle_files(directory, "particles"), thickness(dim == 2 ? thickness : 1.0)
{
}

namespace
{
/// One output's particle data and VTK flags.
template <int dim>
struct Frame
{
  explicit Frame(const double time) : flags(time)
  {
    flags.compression_level = DataOutBase::VtkFlags::best_speed;
  }
  void write_vtu(std::ostream &out) const
  {
    DataOutBase::write_vtu(patches, names, vectors, flags, out);
  }
  std::vector<DataOutBase::Patch<0, dim>> patches;
  std::vector<std::string> names;
  std::vector<std::tuple<unsigned int, unsigned int, std::string,
                         DataComponentInterpretation::DataComponentInterpretation>>
      vectors;
  DataOutBase::VtkFlags flags;
};
} // namespace

template <int dim>
void ParticleOutput<dim>::write(const ParticleStore<dim> &particles, const double time)
{
  Frame<dim> frame(time);
  patches(particles, frame.patches, frame.names, frame.vectors);
  particle_files.add(time, [&](std::ostream &out) { frame.write_vtu(out); });
}

template <int dim>
void ParticleOutput<dim>::write_piece(const ParticleStore<dim> &particles,
                                      const double time, const unsigned int rank,
                                      const unsigned int n_ranks)
{
  Frame<dim> frame(time);
  patches(particles, frame.patches, frame.names, frame.vectors);
  particle_files.add_piece(
      time, rank, n_ranks, [&](std::ostream &out) { frame.write_vtu(out); },
      [&](std::ostream &out, const std::vector<std::string> &pieces)
      {
        DataOutBase::write_pvtu_record(out, pieces, frame.names, frame.vectors,
                                       frame.flags);
      });
}

template <int dim>
void ParticleOutput<dim>::patches(
    const ParticleStore<dim> &particles, std::vector<DataOutBase::Patch<0, dim>> &patches,
    std::vector<std::string> &names,
    std::vector<std::tuple<unsigned int, unsigned int, std::string,
                           DataComponentInterpretation::DataComponentInterpretation>>
        &vectors) const
{
  std::vector<std::size_t> shown;
  for (std::size_t p = 0; p < particles.size(); ++p)
    if (!particles.ghost[p])
      shown.push_back(p);
  const std::size_t n = shown.size();
  // Vectors first, then scalars: the effective stress (what the forces use) and the
  // undamaged one, the max principal effective stress, damage, ids.
  names.clear();
  vectors.clear();
  for (const char *v : {"displacement", "velocity", "crack_normal"})
  {
    vectors.emplace_back(names.size(), names.size() + dim - 1, v,
                         DataComponentInterpretation::component_is_part_of_vector);
    for (unsigned int d = 0; d < dim; ++d)
      names.push_back(v);
  }
  const char *comp[3] = {"x", "y", "z"};
  for (const char *tensor : {"stress_", "undamaged_stress_", "strain_"})
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = i; j < dim; ++j)
        names.push_back(std::string(tensor) + comp[i] + comp[j]);
  for (const char *s :
       {"max_principal_stress", "damage", "failed", "onset_strain", "crack_opening",
        "dissipated_energy_density", "strength_factor", "material_id", "body_id",
        "particle_id", "density", "volume", "size"})
    names.push_back(s);

  patches.resize(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    const std::size_t p = shown[i];
    auto &patch         = patches[i];
    patch.vertices[0]   = particles.position[p];
    patch.patch_index   = i;
    patch.data.reinit(names.size(), 1);
    unsigned int k = 0;
    for (unsigned int d = 0; d < dim; ++d)
      patch.data(k++, 0) = particles.position[p][d] - particles.reference_position[p][d];
    for (unsigned int d = 0; d < dim; ++d)
      patch.data(k++, 0) = particles.velocity[p][d];
    // A run without a fracture model keeps no fracture state: value_at() gives the
    // values such a run would hold.
    const Tensor<1, dim> normal = particles.value_at(particles.crack_normal, p);
    for (unsigned int d = 0; d < dim; ++d)
      patch.data(k++, 0) = normal[d];
    const SymmetricTensor<2, dim> stress = effective_stress(particles, p);
    for (const auto *s : {&stress, &particles.stress[p], &particles.strain[p]})
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = i; j < dim; ++j)
          patch.data(k++, 0) = (*s)[i][j];
    patch.data(k++, 0) = largest_principal(stress);
    patch.data(k++, 0) = particles.damage[p];
    patch.data(k++, 0) = particles.failed[p];
    patch.data(k++, 0) = particles.value_at(particles.onset_strain, p);
    patch.data(k++, 0) = particles.value_at(particles.crack_opening, p);
    patch.data(k++, 0) =
        particles.value_at(particles.dissipated, p) / particles.initial_volume[p];
    patch.data(k++, 0) = particles.value_at(particles.strength, p);
    patch.data(k++, 0) = particles.material_id[p];
    patch.data(k++, 0) = particles.body_id[p];
    patch.data(k++, 0) = particles.id[p];
    patch.data(k++, 0) = particles.density[p];
    patch.data(k++, 0) = particles.volume[p];
    // The side of the particle's domain, to size glyphs in ParaView.
    patch.data(k++, 0) = dim == 2 ? std::sqrt(particles.volume[p] / thickness)
                                  : std::cbrt(particles.volume[p]);
  }
}

template class ParticleOutput<2>;
template class ParticleOutput<3>;
} // namespace lme_mpm
