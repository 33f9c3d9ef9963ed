#ifndef LME_MPM_TESTS_STORE_BYTES_H
#define LME_MPM_TESTS_STORE_BYTES_H

// The bytes of a particle store's fields, for tests that check fields move together.
#include <lme_mpm/particles/particle_store.h>

#include <random>
#include <vector>

namespace lme_mpm_test
{
/// Every byte of every field kept of particle @p p.
template <int dim>
std::vector<unsigned char> particle_bytes(lme_mpm::ParticleStore<dim> &store,
                                          const std::size_t p)
{
  std::vector<unsigned char> b;
  store.for_each_field(
      [&](auto &field)
      {
        const auto *c = reinterpret_cast<const unsigned char *>(&field[p]);
        b.insert(b.end(), c, c + sizeof(field[p]));
      });
  return b;
}

/// Fills every byte of every field kept with draws of @p rng.
template <int dim>
void fill_random_bytes(lme_mpm::ParticleStore<dim> &store, std::mt19937 &rng)
{
  store.for_each_field(
      [&](auto &field)
      {
        for (auto &v : field)
        {
          auto *c = reinterpret_cast<unsigned char *>(&v);
          for (std::size_t k = 0; k < sizeof(v); ++k)
            c[k] = static_cast<unsigned char>(rng());
        }
      });
}
} // namespace lme_mpm_test

#endif
