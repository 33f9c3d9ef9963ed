// Particles packed into messages arrive as they left: every field of the store.
#include <gtest/gtest.h>

#include <lme_mpm/particles/particle_store.h>

#include "../../source/distributed/particle_messages.h"

#include <cstring>
#include <random>

using namespace lme_mpm;

namespace
{
/// Every byte of every field of particle p.
std::vector<unsigned char> bytes_of(ParticleStore<3> &store, const std::size_t p)
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

/// A store whose every field holds distinct bytes.
ParticleStore<3> random_store(const unsigned int n)
{
  ParticleStore<3> store;
  store.resize(n);
  std::mt19937 rng(9);
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
  for (unsigned int p = 0; p < n; ++p)
    store.ghost[p] = 0;
  return store;
}
} // namespace

TEST(ParticleMessages, PackThenUnpackKeepsEveryField)
{
  ParticleStore<3> store = random_store(20);
  std::vector<char> buffer;
  for (const std::size_t p : {3u, 7u, 19u})
    particle_messages::pack(store, p, buffer);
  EXPECT_EQ(buffer.size(), 3 * particle_messages::bytes_per_particle<3>());
  ParticleStore<3> received = random_store(2);
  particle_messages::unpack(buffer, received, 1);
  ASSERT_EQ(received.size(), 5u);
  const std::size_t sent[] = {3, 7, 19};
  for (std::size_t k = 0; k < 3; ++k)
  {
    EXPECT_EQ(received.ghost[2 + k], 1);
    received.ghost[2 + k] = store.ghost[sent[k]];
    EXPECT_EQ(bytes_of(received, 2 + k), bytes_of(store, sent[k])) << k;
  }
}

TEST(ParticleMessages, CompactKeepsTheFlaggedInOrder)
{
  ParticleStore<3> store         = random_store(10);
  ParticleStore<3> copy          = store;
  std::vector<std::uint8_t> keep = {1, 0, 0, 1, 1, 0, 1, 0, 0, 1};
  particle_messages::compact(store, keep);
  ASSERT_EQ(store.size(), 5u);
  std::size_t k = 0;
  for (std::size_t p = 0; p < 10; ++p)
    if (keep[p])
    {
      EXPECT_EQ(bytes_of(store, k++), bytes_of(copy, p));
    }
}

TEST(ParticleMessages, DisplacementsAreThePrefixSums)
{
  std::vector<int> at(4);
  EXPECT_EQ(particle_messages::displacements({3, 0, 5, 2}, at), 10u);
  EXPECT_EQ(at, (std::vector<int>{0, 3, 3, 8}));
}
