#ifndef lme_mpm_base_bisection_h
#define lme_mpm_base_bisection_h

#include <algorithm>
#include <cmath>

namespace lme_mpm
{
/**
 * Halves [@p lo, @p hi] at most @p halvings times: each midpoint m = (lo + hi) / 2
 * becomes the new lo where @p moves_lo(m) holds, else the new hi. It stops once a
 * halving would move neither end (they are neighbouring doubles, so every later
 * halving would repeat it) or the ends have met.
 *
 * Two halvings per round: the midpoint and both candidates for the next midpoint are
 * asked together. Those three evaluations do not depend on each other, so the
 * processor overlaps them, where one halving at a time waits for each answer before
 * it can ask the next question (a root solve inside a particle loop is bound by that
 * latency). The ends are those of one halving at a time, bit for bit, for any
 * @p moves_lo: it is asked at more points, never answered differently, so it must
 * have no side effects.
 */
template <class Side>
void bisect(double &lo, double &hi, const int halvings, const Side &moves_lo)
{
  int i = 0;
  while (i < halvings && hi > lo)
  {
    const double mid = 0.5 * (lo + hi), left = 0.5 * (lo + mid), right = 0.5 * (mid + hi);
    const bool at_mid = moves_lo(mid), at_left = moves_lo(left),
               at_right = moves_lo(right);
    double &first       = at_mid ? lo : hi;
    if (first == mid)
      return;
    first = mid;
    if (++i == halvings || !(hi > lo))
      return;
    // The next midpoint, (lo + hi) / 2 of the halved interval, is one of the two asked.
    const double next = at_mid ? right : left;
    double &second    = (at_mid ? at_right : at_left) ? lo : hi;
    if (second == next)
      return;
    second = next;
    ++i;
  }
}

/**
 * bisect() for an increasing function @p f, moves_lo(m) = !(f(m) > 0), ending at the
 * same ends bit for bit while asking @p f only where the sign of its rounded value is
 * in doubt. A root estimate w (regula falsi, the Illinois variant: exact in one step
 * for a linear @p f, a few steps for a smooth one) and a lower bound @p slope > 0 of
 * f' on [@p lo, @p hi] answer every midpoint m with
 * slope |m - w| > |f(w)| + error(w) + error(m), where @p error(x) bounds the rounding
 * error of f(x): there the exact f(m) has the sign of m - w and a magnitude beyond
 * error(m), so the rounded one has that sign too. The other midpoints, within a few
 * rounding errors of the root, ask @p f. Without a positive @p slope, or if f does not
 * change sign on [lo, hi], it is bisect() of @p f itself.
 */
template <class Function, class ErrorBound>
void bisect_increasing(double &lo, double &hi, const int halvings, const Function &f,
                       const double slope, const ErrorBound &error)
{
  const auto asks_f = [&](const double m) { return !(f(m) > 0); };
  double a = lo, b = hi, fa = f(a), fb = f(b);
  if (!(slope > 0 && fa < 0 && fb > 0))
  {
    bisect(lo, hi, halvings, asks_f);
    return;
  }
  // The evaluated point nearest the root (smallest |f|) is the estimate.
  double w = std::abs(fa) < std::abs(fb) ? a : b, fw = std::min(std::abs(fa), fb);
  int kept = 0; // the end the last step kept: -1 a, 1 b
  for (int i = 0; i < 32; ++i)
  {
    const double x = (a * fb - b * fa) / (fb - fa);
    if (!(x > a && x < b))
      break;
    const double fx = f(x);
    if (std::abs(fx) < fw)
      w = x, fw = std::abs(fx);
    if (!(std::abs(fx) > error(x)))
      break;
    if (fx > 0)
    {
      b = x, fb = fx;
      if (kept == -1)
        fa *= 0.5;
      kept = -1;
    }
    else
    {
      a = x, fa = fx;
      if (kept == 1)
        fb *= 0.5;
      kept = 1;
    }
  }
  const double known = fw + error(w);
  const auto certain = [&](const double m, const double d)
  { return slope * std::abs(d) > known + error(m); };
  // While the midpoints are far from w, one halving at a time with one comparison
  // each (the ends of bisect(), which equal those of one halving at a time). The ends
  // are chosen without a branch: which one moves is a coin toss the processor could
  // not predict.
  int done = 0;
  while (done < halvings && hi > lo)
  {
    const double mid = 0.5 * (lo + hi), d = mid - w;
    if (!certain(mid, d))
      break;
    const bool below = d < 0;
    if (mid == (below ? lo : hi))
      return;
    lo = below ? mid : lo;
    hi = below ? hi : mid;
    ++done;
  }
  bisect(lo, hi, halvings - done,
         [&](const double m)
         {
           const double d = m - w;
           return certain(m, d) ? d < 0 : asks_f(m);
         });
}
} // namespace lme_mpm

#endif
