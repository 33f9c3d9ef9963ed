#ifndef lme_mpm_base_bisection_h
#define lme_mpm_base_bisection_h

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
} // namespace lme_mpm

#endif
