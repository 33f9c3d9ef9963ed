#ifndef LME_MPM_BASE_PARALLEL_H
#define LME_MPM_BASE_PARALLEL_H

#include <deal.II/base/parallel.h>

#include <cstddef>
#include <vector>

namespace lme_mpm
{
namespace parallel
{
/// Particles handed to one task: large enough to amortise scheduling.
constexpr std::size_t grain_size = 1024;

/**
 * Runs f(begin, end) over [0, n) in parallel. Each index is visited once; callers
 * only write to data owned by the index, so results do not depend on threads.
 */
template <class F>
void for_range(const std::size_t n, const F &f)
{
  if (n == 0)
    return;
  if (n <= grain_size)
  {
    f(std::size_t(0), n);
    return;
  }
  dealii::parallel::apply_to_subranges(
      std::size_t(0), n, [&](const std::size_t b, const std::size_t e) { f(b, e); },
      grain_size);
}

/**
 * A sum over [0, n) whose value is bitwise independent of the thread count: the
 * range is cut into fixed blocks, each summed in order, and the block sums are
 * added in order. @p f(begin, end) returns the sum over its range; T supports +=.
 */
template <class T, class F>
T deterministic_sum(const std::size_t n, const F &f, const T zero = T())
{
  constexpr std::size_t block = 4096;
  const std::size_t n_blocks  = (n + block - 1) / block;
  std::vector<T> partial(n_blocks, zero);
  // One task per block: a block is already worth scheduling, and for_range's grain
  // (in particles) would run a few blocks, i.e. every scene's particles, on one thread.
  const auto sum_blocks = [&](const std::size_t b0, const std::size_t b1)
  {
    for (std::size_t b = b0; b < b1; ++b)
      partial[b] = f(b * block, std::min(n, (b + 1) * block));
  };
  if (n_blocks <= 1)
    sum_blocks(0, n_blocks);
  else
    dealii::parallel::apply_to_subranges(std::size_t(0), n_blocks, sum_blocks, 1);
  T total = zero;
  for (const auto &p : partial)
    total += p;
  return total;
}
} // namespace parallel
} // namespace lme_mpm

#endif
