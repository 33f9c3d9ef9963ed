// bisect(): two halvings per round give the ends of one halving at a time, bit for bit.
#include <gtest/gtest.h>

#include <lme_mpm/base/bisection.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>

using namespace lme_mpm;

namespace
{
/// One halving at a time: the loop the fracture models' root solves used before.
template <class Side>
void bisect_one_at_a_time(double &lo, double &hi, const int halvings,
                          const Side &moves_lo)
{
  for (int i = 0; i < halvings && hi > lo; ++i)
  {
    const double mid = 0.5 * (lo + hi);
    double &bound    = moves_lo(mid) ? lo : hi;
    if (bound == mid)
      return;
    bound = mid;
  }
}

std::uint64_t bits(const double x)
{
  std::uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}
} // namespace

TEST(Bisection, TwoHalvingsPerRoundGiveTheEndsOfOneAtATime)
{
  std::mt19937_64 random(20261206);
  std::uniform_real_distribution<double> unit(0, 1);
  std::uniform_int_distribution<int> count(0, 70);
  unsigned int stopped_early = 0, cases = 0;
  for (int trial = 0; trial < 20000; ++trial)
  {
    const double a = std::ldexp(unit(random), int(count(random)) - 35),
                 b = a + std::ldexp(unit(random), int(count(random)) - 35) *
                             (trial % 10 == 0 ? 0.0 : 1.0);
    const double root     = a + (b - a) * (1.2 * unit(random) - 0.1);
    const int halvings    = trial % 3 == 0 ? count(random) : 60;
    const std::uint64_t k = random();
    // A monotone side (the root solves), a side that flips back (any predicate must
    // give the same ends, as nothing is assumed of it), and one that is NaN-like
    // (false) over a band.
    const auto monotone = [&](const double x) { return x < root; };
    const auto noisy    = [&](const double x) { return ((bits(x) * k) >> 61) & 1; };
    const auto banded   = [&](const double x)
    { return !(std::abs(x - root) < 1e-3 * (b - a)) && x < root; };
    const auto check = [&](const auto &side)
    {
      double lo0 = a, hi0 = b, lo1 = a, hi1 = b;
      bisect_one_at_a_time(lo0, hi0, halvings, side);
      bisect(lo1, hi1, halvings, side);
      EXPECT_EQ(bits(lo0), bits(lo1)) << trial;
      EXPECT_EQ(bits(hi0), bits(hi1)) << trial;
      stopped_early +=
          halvings == 60 && hi0 > lo0 && hi0 - lo0 > 0 && std::nextafter(lo0, hi0) == hi0;
      ++cases;
    };
    check(monotone);
    check(noisy);
    check(banded);
  }
  EXPECT_EQ(cases, 60000u);
  // Most 60-halving solves end at neighbouring doubles before the 60th: the stop that
  // the two-per-round loop must reproduce at either of its halvings.
  EXPECT_GT(stopped_early, 10000u);
}

TEST(Bisection, FindsTheRootOfAMonotoneFunction)
{
  // F(w) = w^3 + w - 1 (root 0.6823278038280193...), as the opening solve asks it.
  const auto F = [](const double w) { return w * w * w + w - 1; };
  double lo = 0, hi = 1;
  bisect(lo, hi, 60, [&](const double x) { return !(F(x) > 0); });
  EXPECT_LE(hi - lo, 2 * std::numeric_limits<double>::epsilon());
  EXPECT_NEAR(0.5 * (lo + hi), 0.6823278038280193, 1e-15);
}
