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

template <int dim>
Energies EnergyBalance<dim>::measure(const ParticleStore<dim> &store,
                                     const MaterialSet<dim> &materials) const
{
  const std::size_t n = store.size();
  Energies e;
  e.kinetic = parallel::deterministic_sum<double>(
      n,
      [&](const std::size_t b, const std::size_t end)
      {
        double s = 0;
        for (std::size_t p = b; p < end; ++p)
          if (excluded.empty() || !excluded[store.body_id[p]])
            s += 0.5 * store.mass[p] * store.velocity[p].norm_square();
        return s;
      });
  e.strain = parallel::deterministic_sum<double>(
      n, [&](const std::size_t b, const std::size_t end)
      { return materials.strain_energy(store, b, end); });
  e.dissipated =
      parallel::deterministic_sum<double>(n,
                                          [&](const std::size_t b, const std::size_t end)
                                          {
                                            double s = 0;
                                            for (std::size_t p = b; p < end; ++p)
                                              s += store.dissipated[p];
                                            return s;
                                          });
  e.external_work = external_work;
  return e;
}

template <int dim>
void EnergyBalance<dim>::record(const Energies &e, const bool initial)
{
  if (initial)
    initial_total_energy = e.total();
  energy_scale =
      std::max({energy_scale, std::abs(initial_total_energy),
                e.kinetic + e.strain + e.dissipated, std::abs(e.external_work)});
  const double drift =
      std::abs(e.total() - initial_total_energy) / std::max(energy_scale, 1e-300);
  max_energy_drift = std::max(max_energy_drift, drift);
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
