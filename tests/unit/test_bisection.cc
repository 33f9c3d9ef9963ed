// bisect(): two halvings per round give the ends of one halving at a time, bit for bit.
#include <gtest/gtest.h>

#include <lme_mpm/base/bisection.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iostream>
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

TEST(Bisection, AnIncreasingFunctionAskedNearItsRootGivesTheSameEnds)
{
  // The opening solve of eigensoftening, F(w) = s0 (g(r w) - 1) / M + w / h - e, for
  // linear, bilinear and exponential laws g, with bands from a hundredth of the
  // snap-back limit to just inside it, and strains from the first step of softening
  // to beyond the law's end.
  std::mt19937_64 random(20261207);
  std::uniform_real_distribution<double> unit(0, 1);
  const double eps          = std::numeric_limits<double>::epsilon();
  unsigned long asked_plain = 0, asked_near = 0;
  unsigned int solves = 0;
  for (int trial = 0; trial < 30000; ++trial)
  {
    const int law          = trial % 3;
    const double w_c       = 5e-5 * (0.5 + unit(random)),
                 s0_over_M = 1e-4 * (0.5 + unit(random)), r = 0.5 + unit(random);
    const double w_k = w_c * (0.1 + 0.3 * unit(random)); // the bilinear kink
    const auto g     = [&](const double x)
    {
      if (law == 0)
        return x >= w_c ? 0.0 : 1 - x / w_c;
      if (law == 1)
        return x <= w_k ? 1 - (2.0 / 3.0) * x / w_k
                        : (x >= w_c ? 0.0 : (1.0 / 3.0) * (w_c - x) / (w_c - w_k));
      return x >= w_c ? 0.0 : std::exp(-6.9 * x / w_c);
    };
    const double max_slope = law == 0 ? 1 / w_c
                             : law == 1
                                 ? std::max((2.0 / 3.0) / w_k, (1.0 / 3.0) / (w_c - w_k))
                                 : 6.9 / w_c;
    // h from the snap-back limit h_max = 1 / (s0 r max|g'| / M) down to 1 % of it.
    const double h_max = 1 / (s0_over_M * r * max_slope);
    const double h = h_max * (trial % 50 == 0 ? 1 - 1e-6 : 0.01 + 0.98 * unit(random));
    const double w_end = w_c / r;
    const double e = std::ldexp(unit(random), -int(60 * unit(random))) * 1.2 * w_end / h;
    unsigned long *asked = nullptr;
    const auto F         = [&](const double w)
    {
      ++*asked;
      return s0_over_M * (g(r * w) - 1) + w / h - e;
    };
    asked = &asked_plain;
    if (!(F(w_end) > 0))
      continue;
    double lo0 = 0, hi0 = w_end, lo1 = 0, hi1 = w_end;
    bisect(lo0, hi0, 60, [&](const double x) { return !(F(x) > 0); });
    asked              = &asked_near;
    const double slope = (1 / h - s0_over_M * r * max_slope) * (1 - 1e-9);
    bisect_increasing(lo1, hi1, 60, F, slope,
                      [&](const double w)
                      { return 64 * eps * (s0_over_M + std::abs(w) / h + std::abs(e)); });
    EXPECT_EQ(bits(lo0), bits(lo1)) << trial;
    EXPECT_EQ(bits(hi0), bits(hi1)) << trial;
    ++solves;
  }
  EXPECT_GT(solves, 20000u);
  std::cout << "evaluations per solve: bisect " << double(asked_plain) / solves
            << ", near the root " << double(asked_near) / solves << std::endl;
  EXPECT_LT(asked_near, asked_plain / 3);

  // Without a positive slope bound it bisects the function itself.
  double lo0 = 0, hi0 = 1, lo1 = 0, hi1 = 1;
  const auto cubic = [](const double x) { return (x - 0.3) * (x - 0.3) * (x - 0.3); };
  bisect(lo0, hi0, 60, [&](const double x) { return !(cubic(x) > 0); });
  bisect_increasing(lo1, hi1, 60, cubic, 0.0, [](double) { return 0.0; });
  EXPECT_EQ(bits(lo0), bits(lo1));
  EXPECT_EQ(bits(hi0), bits(hi1));
}
