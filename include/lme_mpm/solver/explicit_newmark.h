#ifndef LME_MPM_SOLVER_EXPLICIT_NEWMARK_H
#define LME_MPM_SOLVER_EXPLICIT_NEWMARK_H

#include <deal.II/base/tensor.h>

#include <lme_mpm/base/dealii.h>
#include <lme_mpm/grid/nodal_fields.h>

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

  /**
   * The velocity the corrector gives field @p F of @p nodes at the end of the step,
   * lumped on the node: from its momentum and mass-weighted acceleration of the start
   * of the step and its acceleration now (what contact compares and corrects).
   */
  template <int dim>
  Tensor<1, dim> trial_velocity(const NodalFields<dim> &nodes, const unsigned int F,
                                const double dt) const
  {
    return corrected_velocity(nodes.momentum[F] / nodes.mass[F],
                              nodes.mass_acceleration[F] / nodes.mass[F],
                              nodes.acceleration[F], dt);
  }
};
} // namespace lme_mpm

#endif
