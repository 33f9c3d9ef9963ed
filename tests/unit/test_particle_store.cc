// ParticleStore: the counting sort by cell keeps each particle's fields together.
#include <deal.II/base/multithread_info.h>

#include <gtest/gtest.h>

#include <lme_mpm/grid/background_grid.h>
#include <lme_mpm/output/particle_output.h>
#include <lme_mpm/output/probes.h>
#include <lme_mpm/particles/particle_store.h>

#include "store_bytes.h"
#include "test_helpers.h"

#include <cmath>
#include <filesystem>
#include <random>

using namespace lme_mpm;

TEST(ParticleStore, CountingSortKeepsFieldsTogether)
{
  ParticleStore<2> store;
  std::mt19937 rng(7);
  for (unsigned int p = 0; p < 500; ++p)
  {
    store.add(Point<2>(p, 0), p + 1.0, 1.0, 0, 0);
    store.cell[p] = rng() % 37;
  }
  const std::vector<double> masses = store.mass;
  const std::uint64_t before       = store.order_version();
  EXPECT_NE(store.sorted_version(), before); // no sort yet
  EXPECT_TRUE(store.sort_by_cell(37));
  // The permutation says where each particle came from, for caches kept outside.
  EXPECT_EQ(store.order_version(), before + 1);
  EXPECT_EQ(store.sorted_version(), store.order_version());
  ASSERT_EQ(store.sort_permutation().size(), store.size());
  for (std::size_t p = 0; p < store.size(); ++p)
    EXPECT_EQ(store.mass[p], masses[store.sort_permutation()[p]]);
  for (std::size_t p = 0; p < store.size(); ++p)
  {
    if (p > 0)
    {
      EXPECT_LE(store.cell[p - 1], store.cell[p]);
      if (store.cell[p - 1] == store.cell[p]) // stable
      {
        EXPECT_LT(store.id[p - 1], store.id[p]);
      }
    }
    EXPECT_EQ(store.mass[p], store.id[p] + 1.0);
    EXPECT_EQ(store.position[p][0], double(store.id[p]));
  }
  const auto &off = store.cell_offsets();
  for (unsigned int c = 0; c < 37; ++c)
    for (std::size_t p = off[c]; p < off[c + 1]; ++p)
      EXPECT_EQ(store.cell[p], c);
  EXPECT_FALSE(store.sort_by_cell(37)); // already sorted: no reorder
  EXPECT_EQ(store.sorted_version(), store.order_version());
  store.mark_reordered(); // a change the permutation does not describe
  EXPECT_NE(store.sorted_version(), store.order_version());
}

TEST(ParticleStore, SortMovesEveryKeptFieldAsACopyWould)
{
  // The sort moves fields in place along the permutation's cycles; the result must be
  // what gathering each field through the permutation gives, for an order where most
  // particles keep their place (a step) and for a shuffled one (the first sort).
  for (const bool shuffled : {false, true})
    for (const bool keep_all : {true, false})
    {
      ParticleStore<2> store;
      store.keep_state({keep_all, keep_all});
      std::mt19937 rng(shuffled ? 3 : 5);
      const unsigned int n = 2000, n_cells = 400;
      for (unsigned int p = 0; p < n; ++p)
        store.add(Point<2>(p, 0), 1.0, 1.0, 0, 0);
      lme_mpm_test::fill_random_bytes(store, rng);
      for (unsigned int p = 0; p < n; ++p)
      {
        store.id[p] = p;
        // Sorted but for one particle in 50 that crossed into a neighbouring cell.
        store.cell[p] = shuffled ? rng() % n_cells
                                 : std::min(n_cells - 1, p / 5 + (p % 50 == 7 ? 1 : 0));
      }
      std::vector<std::vector<unsigned char>> before(n);
      for (unsigned int p = 0; p < n; ++p)
        before[p] = lme_mpm_test::particle_bytes(store, p);
      ASSERT_TRUE(store.sort_by_cell(n_cells));
      const auto &from  = store.sort_permutation();
      std::size_t moved = 0;
      for (unsigned int q = 0; q < n; ++q)
      {
        moved += from[q] != q;
        EXPECT_EQ(lme_mpm_test::particle_bytes(store, q), before[from[q]]) << q;
      }
      EXPECT_GT(moved, 0u);
      if (!shuffled)
      {
        EXPECT_LT(moved, n / 10);
      }
      EXPECT_EQ(store.lme_lambda.size(), keep_all ? n : 0u);
      EXPECT_EQ(store.crack_normal.size(), keep_all ? n : 0u);
    }
}

TEST(ParticleStore, DroppedStateStaysEmptyAndReturnsZeroed)
{
  ParticleStore<2> store;
  store.keep_state({false, false});
  for (unsigned int p = 0; p < 10; ++p)
    store.add(Point<2>(p, 0), 1.0, 1.0, 0, 0);
  store.resize(12);
  for (unsigned int p = 0; p < 12; ++p)
    store.cell[p] = 11 - p;
  EXPECT_TRUE(store.sort_by_cell(12));
  EXPECT_EQ(store.size(), 12u);
  EXPECT_TRUE(store.lme_lambda.empty() && store.lme_position.empty() &&
              store.lme_lambda_rate.empty());
  EXPECT_TRUE(store.onset_strain.empty() && store.onset_stress.empty() &&
              store.crack_opening.empty() && store.dissipated.empty() &&
              store.strength.empty() && store.crack_normal.empty() &&
              store.crack_coupling.empty());
  EXPECT_EQ(store.damage.size(), 12u); // every run's stress reads it
  EXPECT_EQ(store.failed.size(), 12u);
  ParticleStore<2> full;
  EXPECT_EQ(store.bytes_per_particle() + 64 + 64, full.bytes_per_particle());
  // Kept again: sized as the others, zeroed, and each strength its material's.
  store.keep_state({true, true});
  ASSERT_EQ(store.strength.size(), 12u);
  ASSERT_EQ(store.lme_lambda_rate.size(), 12u);
  for (unsigned int p = 0; p < 12; ++p)
  {
    EXPECT_EQ(store.strength[p], 1.0);
    EXPECT_EQ(store.dissipated[p], 0.0);
    EXPECT_EQ(store.lme_lambda[p].norm(), 0.0);
  }
}

TEST(ParticleStore, ADroppedFieldReadsAsTheValueAKeptOneHoldsInSuchARun)
{
  // The state checksum walks every field through value_at(), dropped ones as their
  // dropped_value(): a run that drops the state it does not use must hash as one that
  // kept it untouched.
  const auto bytes = [](ParticleStore<2> &store, const std::size_t p)
  {
    std::vector<unsigned char> b;
    store.for_all_fields(
        [&](auto &field)
        {
          const auto value = store.value_at(field, p);
          const auto *c    = reinterpret_cast<const unsigned char *>(&value);
          b.insert(b.end(), c, c + sizeof(value));
        });
    return b;
  };
  ParticleStore<2> kept, dropped;
  dropped.keep_state({false, false});
  for (auto *store : {&kept, &dropped})
    for (unsigned int p = 0; p < 3; ++p)
    {
      store->add(Point<2>(p, 1), 2.0, 0.5, 0, 0);
      store->velocity[p][1] = -1.0 * p;
      store->damage[p]      = 0.25;
    }
  for (unsigned int p = 0; p < 3; ++p)
    EXPECT_EQ(bytes(kept, p), bytes(dropped, p)) << p;
  // A kept field that a run changed reads differently: the walk sees the fields.
  kept.strength[1] = 0.9;
  EXPECT_NE(bytes(kept, 1), bytes(dropped, 1));
}
