#ifndef LME_MPM_SOLVER_EXPLICIT_NEWMARK_H
#define LME_MPM_SOLVER_EXPLICIT_NEWMARK_H

namespace lme_mpm
{
/**
 * Explicit Newmark (beta = 0) in predictor-corrector form, the update used on the
 * grid and the particles (doc/theory.md):
 *   displacement predictor  u^{n+1} = u^n + dt w,  w = v^n + dt/2 a^n
 *   corrector               v^{n+1} = v^n + dt ((1 - gamma) a^n + gamma a^{n+1})
 * with a^{n+1} = M^{-1} f(u^{n+1}). gamma = 1/2 is the central-difference scheme:
 * second order and free of numerical dissipation; gamma > 1/2 damps at first order.
 * The displacement predictor does not depend on gamma, so the strain increment is
 * always consistent with the displacement actually applied.
 */
struct ExplicitNewmark
{
  double gamma = 0.5;

  /// Velocity whose product with dt is the displacement increment.
  template <class T>
  T displacement_rate(const T &v, const T &a, const double dt) const
  {
    return v + (0.5 * dt) * a;
  }

  template <class T>
  T corrected_velocity(const T &v, const T &a_old, const T &a_new, const double dt) const
  {
    return v + dt * ((1 - gamma) * a_old + gamma * a_new);
  }
};
} // namespace lme_mpm

#endif
