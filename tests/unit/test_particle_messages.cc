// Particles packed into messages arrive as they left: every field of the store.
#include <gtest/gtest.h>

#include <lme_mpm/particles/particle_store.h>

#include "../../source/distributed/particle_messages.h"
#include "store_bytes.h"

#include <cstring>
#include <random>

using namespace lme_mpm;

namespace
{
/// A store whose every field kept holds distinct bytes.
ParticleStore<3> random_store(const unsigned int n,
                              const ParticleStore<3>::OptionalState &kept = {})
{
  ParticleStore<3> store;
  store.keep_state(kept);
  store.resize(n);
  std::mt19937 rng(9);
  lme_mpm_test::fill_random_bytes(store, rng);
  for (unsigned int p = 0; p < n; ++p)
    store.ghost[p] = 0;
  return store;
}
} // namespace

TEST(ParticleMessages, PackThenUnpackKeepsEveryField)
{
  // Every combination of the optional state: a run that drops some sends the rest.
  std::size_t all_fields = 0;
  for (const bool shape : {true, false})
    for (const bool fracture : {true, false})
    {
      const ParticleStore<3>::OptionalState kept{shape, fracture};
      ParticleStore<3> store = random_store(20, kept);
      std::vector<char> buffer;
      for (const std::size_t p : {3u, 7u, 19u})
        particle_messages::pack(store, p, buffer);
      EXPECT_EQ(buffer.size(), 3 * store.bytes_per_particle());
      if (shape && fracture)
        all_fields = store.bytes_per_particle();
      else // 3D: 120 bytes of warm start, 72 of fracture state
        EXPECT_EQ(store.bytes_per_particle(),
                  all_fields - (shape ? 0 : 120) - (fracture ? 0 : 72));
      ParticleStore<3> received = random_store(2, kept);
      particle_messages::unpack(buffer, received, 1);
      ASSERT_EQ(received.size(), 5u);
      EXPECT_EQ(received.lme_lambda.size(), shape ? 5u : 0u);
      EXPECT_EQ(received.strength.size(), fracture ? 5u : 0u);
      const std::size_t sent[] = {3, 7, 19};
      for (std::size_t k = 0; k < 3; ++k)
      {
        EXPECT_EQ(received.ghost[2 + k], 1);
        received.ghost[2 + k] = store.ghost[sent[k]];
        EXPECT_EQ(lme_mpm_test::particle_bytes(received, 2 + k),
                  lme_mpm_test::particle_bytes(store, sent[k]))
            << k;
      }
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
      EXPECT_EQ(lme_mpm_test::particle_bytes(store, k++),
                lme_mpm_test::particle_bytes(copy, p));
    }
}

TEST(ParticleMessages, DisplacementsAreThePrefixSums)
{
  std::vector<int> at(4);
  EXPECT_EQ(particle_messages::displacements({3, 0, 5, 2}, at), 10u);
  EXPECT_EQ(at, (std::vector<int>{0, 3, 3, 8}));
}

TEST(ParticleMessages, RefilledGhostsAreThoseAppendedInTheirOldSlots)
{
  for (const bool fracture : {true, false})
  {
    // A rank's store: owned particles and ghosts interleaved (sorted by cell), ids
    // distinct.
    const ParticleStore<3>::OptionalState kept{true, fracture};
    ParticleStore<3> here                 = random_store(12, kept);
    const std::vector<std::uint8_t> ghost = {0, 1, 1, 0, 0, 1, 0, 1, 0, 0, 1, 0};
    for (std::size_t p = 0; p < here.size(); ++p)
      here.id[p] = 100 + 7 * p, here.ghost[p] = ghost[p];
    // Their new states, as the owners send them: in another order.
    ParticleStore<3> owners  = random_store(5, kept);
    const std::size_t from[] = {7, 1, 10, 5, 2}; // owners' particle k is here's from[k]
    std::vector<char> buffer;
    for (std::size_t k = 0; k < 5; ++k)
    {
      owners.id[k] = here.id[from[k]];
      particle_messages::pack(owners, k, buffer);
    }
    ParticleStore<3> refilled = here;
    std::vector<std::size_t> slots;
    ASSERT_TRUE(particle_messages::refill_ghosts(buffer, refilled, slots));
    EXPECT_EQ(slots, (std::vector<std::size_t>{7, 1, 10, 5, 2}));
    // Again, with the slots found: the same particles.
    {
      ParticleStore<3> again = here;
      ASSERT_TRUE(particle_messages::refill_ghosts(buffer, again, slots));
      for (std::size_t p = 0; p < here.size(); ++p)
        EXPECT_EQ(lme_mpm_test::particle_bytes(again, p),
                  lme_mpm_test::particle_bytes(refilled, p));
    }
    // Stale slots (two ghosts swapped their places since): found afresh.
    {
      ParticleStore<3> swapped = here;
      std::swap(swapped.id[1], swapped.id[7]);
      ASSERT_TRUE(particle_messages::refill_ghosts(buffer, swapped, slots));
      EXPECT_EQ(slots, (std::vector<std::size_t>{1, 7, 10, 5, 2}));
      EXPECT_EQ(lme_mpm_test::particle_bytes(swapped, 7),
                lme_mpm_test::particle_bytes(refilled, 1));
      slots = {7, 1, 10, 5, 2};
    }
    ASSERT_EQ(refilled.size(), here.size());
    for (std::size_t p = 0; p < here.size(); ++p)
      if (!ghost[p])
      {
        EXPECT_EQ(lme_mpm_test::particle_bytes(refilled, p),
                  lme_mpm_test::particle_bytes(here, p))
            << p;
      }
    for (std::size_t k = 0; k < 5; ++k)
    {
      EXPECT_EQ(refilled.ghost[from[k]], 1);
      refilled.ghost[from[k]] = owners.ghost[k];
      EXPECT_EQ(lme_mpm_test::particle_bytes(refilled, from[k]),
                lme_mpm_test::particle_bytes(owners, k))
          << k;
    }

    // Not the same ghosts: one id unknown here, one ghost fewer, or one more.
    for (const int change : {0, 1, 2})
    {
      std::vector<char> other;
      for (std::size_t k = 0; k < (change == 1 ? 4u : 5u); ++k)
      {
        owners.id[k] = here.id[from[k]] + (change == 0 && k == 3 ? 1 : 0);
        particle_messages::pack(owners, k, other);
      }
      if (change == 2)
      {
        owners.id[0] = 999;
        particle_messages::pack(owners, 0, other);
      }
      ParticleStore<3> unchanged         = here;
      std::vector<std::size_t> old_slots = slots;
      EXPECT_FALSE(particle_messages::refill_ghosts(other, unchanged, old_slots))
          << change;
      for (std::size_t p = 0; p < here.size(); ++p)
        EXPECT_EQ(lme_mpm_test::particle_bytes(unchanged, p),
                  lme_mpm_test::particle_bytes(here, p))
            << change << ' ' << p;
    }
  }
}
