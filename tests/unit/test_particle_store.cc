// ParticleStore: the counting sort by cell keeps each particle's fields together.
#include <deal.II/base/multithread_info.h>

#include <gtest/gtest.h>

#include <lme_mpm/grid/background_grid.h>
#include <lme_mpm/output/particle_output.h>
#include <lme_mpm/output/probes.h>
#include <lme_mpm/particles/particle_store.h>

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
