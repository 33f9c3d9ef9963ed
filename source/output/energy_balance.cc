#include <lme_mpm/base/parallel.h>
#include <lme_mpm/output/energy_balance.h>

#include <algorithm>
#include <cmath>

namespace lme_mpm
{
std::map<std::string, double> Energies::as_map() const
{
  return {{"kinetic_energy", kinetic},
          {"strain_energy", strain},
          {"dissipated_energy", dissipated},
          {"external_work", external_work},
          {"total_energy", total()}};
}

double Energies::in_play() const
{
  return std::max(kinetic + strain + dissipated, std::abs(external_work));
}

template <int dim>
Energies EnergyBalance<dim>::measure(const ParticleStore<dim> &store,
                                     const MaterialSet<dim> &materials) const
{
  // One pass: kinetic, strain and dissipated energy of each block of particles. A
  // material sums its strain energy over ranges of particles, so the ghosts of a
  // distributed run split a block into the ranges of owned particles between them.
  const auto block = [&](const std::size_t b, const std::size_t end)
  {
    Tensor<1, 3> s;
    std::size_t from = b;
    for (std::size_t p = b; p <= end; ++p)
    {
      if (p == end || store.ghost[p])
      {
        if (p > from)
          s[1] += materials.strain_energy(store, from, p);
        from = p + 1;
        continue;
      }
      if (excluded.empty() || !excluded[store.body_id[p]])
        s[0] += 0.5 * store.mass[p] * store.velocity[p].norm_square();
      s[2] += store.value_at(store.dissipated, p);
    }
    return s;
  };
  const Tensor<1, 3> sums =
      parallel::deterministic_sum<Tensor<1, 3>>(store.size(), block);
  Energies e;
  e.kinetic       = sums[0];
  e.strain        = sums[1];
  e.dissipated    = sums[2];
  e.external_work = external_work;
  return e;
}

template <int dim>
Energies EnergyBalance<dim>::measure(const ParticleStore<dim> &store,
                                     const MaterialSet<dim> &materials,
                                     const RankReductions &ranks) const
{
  Energies e               = measure(store, materials);
  std::vector<double> sums = {e.kinetic, e.strain, e.dissipated};
  ranks.sum(sums);
  e.kinetic    = sums[0];
  e.strain     = sums[1];
  e.dissipated = sums[2];
  return e;
}

template <int dim>
void EnergyBalance<dim>::track(const Energies &e, const bool initial)
{
  if (initial)
    initial_total_energy = e.total();
  energy_scale  = std::max({energy_scale, std::abs(initial_total_energy), e.in_play()});
  max_abs_drift = std::max(max_abs_drift, std::abs(e.total() - initial_total_energy));
}

template <int dim>
void EnergyBalance<dim>::write_header(std::ostream &out)
{
  out << "kinetic_energy,strain_energy,dissipated_energy,external_work,total_energy";
}

template <int dim>
void EnergyBalance<dim>::write_row(std::ostream &out, const Energies &e)
{
  out << e.kinetic << "," << e.strain << "," << e.dissipated << "," << e.external_work
      << "," << e.total();
}

template class EnergyBalance<2>;
template class EnergyBalance<3>;
} // namespace lme_mpm
