#include <lme_mpm/base/format.h>
#include <lme_mpm/base/parameters.h>
#include <lme_mpm/shape_functions/tensor_product.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>

#include "lme_kernels.h"
#include "lme_support.h"
#include <lme_mpm/shape_functions/lme_simd.h>

namespace lme_mpm
{
namespace shape_functions
{
using namespace lme_kernels;

/**
 * Local maximum-entropy approximants (Arroyo & Ortiz 2006):
 *   N_I(x) = exp(-beta |x - x_I|^2 + lambda . (x - x_I)) / Z(x, lambda),
 * with beta = gamma / h^2 and lambda the minimiser of log Z, which enforces exact
 * reproduction of linear fields. They are smooth, non-negative and have a
 * Kronecker-delta-like behaviour on the boundary, which is why the fracture
 * simulations use them; gamma trades locality (large) against smoothness (small).
 *
 * On a uniform grid h is the spacing. On a graded grid each node carries its own
 * beta_I = gamma / h_I^2 (Arroyo & Ortiz's nodal locality), h_I the smallest over
 * directions of the node's spacing (BackgroundGrid::nodal_spacing), so N_I and
 * grad N_I stay continuous where cells change size; a beta taken from the cell holding
 * the particle would jump there. The exponent is then -beta_I |x - x_I|^2 +
 * lambda . (x - x_I), and the gradient gains the terms of a node-dependent beta
 * (gradients()).
 *
 * The weights are truncated where exp(-beta_I |x - x_I|^2) < tolerance, i.e. at
 * R_I = h_I sqrt(-ln(tolerance) / gamma). lambda is found by Newton's method on the
 * convex log Z (with a third-order correction near the solution) and a Wolfe line search
 * (plain Newton diverges for gamma >~ 6.8), in coordinates scaled by h, warm-started from
 * the particle's previous multiplier (ParticleStore::lme_lambda) extrapolated along
 * its motion since then; steps that small are taken with a Taylor polynomial in place
 * of the exponentials, so a typical explicit step costs one exponential pass. Any
 * particle where the solve cannot succeed (outside the grid, not strictly inside the hull
 * of its nodes, no convergence) stops the run with ExcShapeFunctionFailure.
 *
 * A particle needs a node within reach on every side: on square cells gamma <= 11 in
 * 2D and 9.2 in 3D with the default cut-off, less on elongated cells of a graded grid
 * (about R^2 >= max_d (s_d^2 + sum_{e != d} (s_e / 2)^2) for a cell of spacings s).
 */
/// The entries of the local max-ent functions, declared and read from this one list.
struct LmeEntries
{
  double gamma = 1.8, tolerance = 1e-6, newton_tolerance = 1e-12;
  unsigned int max_iterations = 50;
  std::string kernel          = "auto";

  void entries(EntryList &list)
  {
    list.add("LME gamma", gamma, "1.8", Patterns::Double(0.1, 100),
             "Locality gamma = beta h^2 of the local max-ent shape functions (h: local "
             "node spacing). Larger values give more local functions, tending to linear "
             "interpolation; smaller ones give smoother, wider functions. Common: 1.8 "
             "to 4.");
    list.add("LME tolerance", tolerance, "1e-6", Patterns::Double(1e-14, 1e-2),
             "Support cut-off of the local max-ent functions: nodes with exp(-gamma "
             "|x - x_I|^2 / h^2) below this are dropped, so the support radius is R = h "
             "sqrt(-ln(tolerance) / gamma).");
    list.add("LME Newton tolerance", newton_tolerance, "1e-12",
             Patterns::Double(1e-15, 1e-4),
             "The Newton solve for the local max-ent multiplier stops when |sum_I N_I "
             "(x - x_I)| < tolerance * h, i.e. when linear fields are reproduced to "
             "this fraction of the spacing.");
    list.add("LME maximum iterations", max_iterations, "50", Patterns::Integer(1, 1000),
             "Newton iterations allowed per particle and step; a particle needing more "
             "stops the run with an error.");
    list.add("LME kernel", kernel, "auto", Patterns::Selection("auto|scalar"),
             "Instruction set of the 2D exponential and moment passes: auto takes AVX2 "
             "with FMA where the processor has them (results differ from scalar in "
             "the last bits), scalar the portable code on any processor.");
  }
};

template <int dim>
class LME : public ShapeFunction<dim>
{
public:
  static void declare_parameters(ParameterHandler &prm)
  {
    EntryList::declare<LmeEntries>(prm);
  }

  LME(ParameterHandler &prm, const ShapeFunctionContext<dim> &context)
      : LME(EntryList::parse<LmeEntries>(prm), context)
  {
  }

  LME(const LmeEntries &in, const ShapeFunctionContext<dim> &context)
      : gamma(in.gamma), newton_tol(in.newton_tolerance),
        cheap_step_limit(std::pow(24 * newton_tol, 0.25)),
        max_iterations(in.max_iterations),
        radius_over_h(std::sqrt(-std::log(in.tolerance) / gamma)),
        kernels(lme_simd::select_kernels(in.kernel)),
        support(*context.grid, radius_over_h, gamma)
  {
  }

  std::string name() const override { return "lme"; }
  bool keeps_particle_state() const override { return true; }
  unsigned int max_nodes_per_particle() const override { return support.max_nodes(); }
  double support_radius(const BackgroundGrid<dim> &) const override
  {
    return support.widest_radius();
  }
  double node_support_radius(const BackgroundGrid<dim> &,
                             const std::array<unsigned int, dim> &node) const override
  {
    return support.node_radius(node);
  }

  void compute(ParticleStore<dim> &particles, const std::size_t begin,
               const std::size_t end, Connectivity<dim> &conn) const override
  {
    Assert(conn.stride >= support.max_nodes(), ExcInternalError());
    AssertThrow(particles.kept_state().shape_function,
                ExcMessage("LME shape functions need the particles' warm-start state, "
                           "which this particle store has dropped"));
    Scratch scratch{support.make_offsets()};
    const bool graded = support.is_graded();
    for (std::size_t p = begin; p < end; ++p)
    {
      const std::size_t row = p * conn.stride;
      const auto fail_at_p  = [&](const auto &...what) { fail(particles, p, what...); };
      const Point<dim> &x   = particles.position[p];
      double h;
      // The cell locate_and_sort() found this step: no second search.
      const unsigned int cell = particles.cell[p];
      const unsigned int n =
          graded ? support.template set_up<true>(x, cell, &conn.nodes[row], scratch, h,
                                                 fail_at_p)
                 : support.template set_up<false>(x, cell, &conn.nodes[row], scratch, h,
                                                  fail_at_p);
      const Solution solution =
          solve(particles, p, n, warm_start(particles, p, h), &conn.N[row], scratch);
      gradients(particles, p, n, h, scratch, &conn.N[row], solution, &conn.grad_N[row]);
      conn.n_nodes[p] = n;
    }
    n_solves += scratch.solves;
    n_iterations += scratch.iterations;
    n_evaluations += scratch.evaluations;
    n_cheap_steps += scratch.cheap;
    unsigned int seen = max_iterations_seen.load();
    while (scratch.max_iterations > seen &&
           !max_iterations_seen.compare_exchange_weak(seen, scratch.max_iterations))
    {
    }
  }

  std::vector<std::pair<std::string, double>> statistics() const override
  {
    const double solves = n_solves.load(), iterations = n_iterations.load();
    return {
        {"lme_solves", solves},
        {"lme_newton_iterations", iterations},
        {"lme_mean_newton_iterations", solves > 0 ? iterations / solves : 0.0},
        {"lme_max_newton_iterations", double(max_iterations_seen.load())},
        {"lme_evaluations", double(n_evaluations.load())},
        {"lme_mean_evaluations", solves > 0 ? n_evaluations.load() / solves : 0.0},
        {"lme_polynomial_steps", double(n_cheap_steps.load())},
        {"lme_mean_polynomial_steps", solves > 0 ? n_cheap_steps.load() / solves : 0.0}};
  }

private:
  /// Scratch of one compute() call, shared by its particles: their nodes' offsets,
  /// and their statistics.
  struct Scratch : LmeSupport<dim>::Offsets
  {
    std::uint64_t solves = 0, iterations = 0, evaluations = 0, cheap = 0;
    unsigned int max_iterations = 0;
  };

  /// The converged multiplier mu = lambda h, and r and J at it.
  struct Solution
  {
    Tensor<1, dim> mu, r;
    Tensor<2, dim> J;
  };

  /// Stops the run: particle p's shape functions fail for the streamed reason @p what.
  template <typename... T>
  void fail(const ParticleStore<dim> &particles, const std::size_t p,
            const T &...what) const
  {
    std::ostringstream s;
    (s << ... << what);
    AssertThrow(false,
                ExcShapeFunctionFailure("lme", particles.id[p],
                                        point_to_string(particles.position[p]), s.str()));
  }

  /// Warm start mu = lambda h: the last multiplier extrapolated along the motion since
  /// that solve. On r(mu, x) = 0 the implicit function theorem gives d mu / d(x / h) =
  /// 2 gamma I - J^-1, so the first residual is second order in the displacement.
  static Tensor<1, dim> warm_start(const ParticleStore<dim> &particles,
                                   const std::size_t p, const double h)
  {
    const Tensor<1, dim> dx = particles.position[p] - particles.lme_position[p];
    return (particles.lme_lambda[p] + particles.lme_lambda_rate[p] * dx) * h;
  }

  /// evaluate() of lme_kernels.h; in 2D by the selected kernels.
  void evaluate_2d_or(const Scratch &scratch, const unsigned int n,
                      const Tensor<1, dim> &mu, double *N, double &F, Tensor<1, dim> &r,
                      Tensor<2, dim> &J) const
  {
    if constexpr (dim == 2)
    {
      lme_simd::Moments2 m;
      const double f_max = kernels.exponential(scratch.a.data(), scratch.y0.data(),
                                               scratch.y1.data(), n, mu[0], mu[1], N, m);
      F                  = f_max + normalise_moments(m, N, n, r, J);
    }
    else
      evaluate(scratch.a.data(), scratch.y.data(), n, mu, N, F, r, J);
  }

  /// polynomial_step() of lme_kernels.h; in 2D by the selected kernels.
  void polynomial_step_2d_or(const Scratch &scratch, const unsigned int n,
                             const Tensor<1, dim> &step, double *N, double &F,
                             Tensor<1, dim> &r, Tensor<2, dim> &J) const
  {
    if constexpr (dim == 2)
    {
      lme_simd::Moments2 m;
      kernels.polynomial(scratch.y0.data(), scratch.y1.data(), n, step[0], step[1], r[0],
                         r[1], N, m);
      const double step_r = step * r;
      F += step_r + normalise_moments(m, N, n, r, J);
    }
    else
      polynomial_step(scratch.y.data(), n, step, N, F, r, J);
  }

  /// normalise() of lme_kernels.h from raw moments already summed (2D).
  static double normalise_moments(const lme_simd::Moments2 &m, double *N,
                                  const unsigned int n, Tensor<1, dim> &r,
                                  Tensor<2, dim> &J)
  {
    const double inv_Z = 1 / m.Z;
    for (unsigned int I = 0; I < n; ++I)
      N[I] *= inv_Z;
    r[0] = m.r0 * inv_Z, r[1] = m.r1 * inv_Z;
    J[0][0] = m.j00 * inv_Z - r[0] * r[0];
    J[0][1] = J[1][0] = m.j01 * inv_Z - r[0] * r[1];
    J[1][1]           = m.j11 * inv_Z - r[1] * r[1];
    return std::log(m.Z);
  }

  /// Minimises log Z over mu from the warm start @p mu (see the class documentation),
  /// leaving the N_I in @p N. Stops the run if it does not converge to a regular J.
  Solution solve(const ParticleStore<dim> &particles, const std::size_t p,
                 const unsigned int n, Tensor<1, dim> mu, double *N,
                 Scratch &scratch) const
  {
    Tensor<1, dim> r, r_trial, mu_trial;
    Tensor<2, dim> J, J_trial;
    double F, F_trial;
    unsigned int it = 0, cheap = 0; // all steps; those without exponentials
    const auto report = [&](const char *what)
    {
      fail(particles, p, what, " after ", it, " Newton iterations (gamma = ", gamma, ", ",
           n, " nodes): |r|/h = ", r.norm(), " (tolerance ", newton_tol,
           "), |lambda| h = ", mu.norm());
    };
    // J is a covariance of the y_I; it loses rank only if the weights
    // concentrate on a lower-dimensional set of nodes.
    const auto singular = [](const Tensor<2, dim> &J)
    {
      const double scale = trace(J) / dim;
      return !(determinant(J) > 1e-12 * std::pow(scale, dim));
    };
    const Tensor<1, dim> *y = scratch.y.data();
    evaluate_2d_or(scratch, n, mu, N, F, r, J);
    ++scratch.evaluations;
    while (!(r.norm() < newton_tol))
    {
      if (it == max_iterations)
        report("not converged ('LME maximum iterations')");
      if (!std::isfinite(F) || singular(J))
        report("singular Hessian");
      // Newton step s = -J^-1 r plus, where it is a small correction, Chebyshev's
      // third-order term -J^-1 T(s, s) / 2 with T = dJ/dmu the third cumulant
      // sum_I N_I z_I (x) z_I (x) z_I, z_I = y_I - r. It costs one pass without
      // exponentials and turns the quadratic convergence cubic: a warm start then
      // needs 1-2 steps instead of 2-3, and fewer particles near grid lines at
      // large gamma (small J, so lambda moves a lot with x) need a fourth.
      const Tensor<2, dim> J_inv_step = invert(J);
      Tensor<1, dim> step             = -(J_inv_step * r);
      // Near the solution (the common case after the warm start) a polynomial step:
      // its |t| <= |step| (R / h + |r|) is below cheap_step_limit.
      if (step.norm() * (radius_over_h + r.norm()) < cheap_step_limit)
      {
        polynomial_step_2d_or(scratch, n, step, N, F, r, J);
        mu += step;
        ++it, ++cheap;
        continue;
      }
      {
        if constexpr (dim == 2) // the 2D set-ups fill only y0 and y1
          for (unsigned int I = 0; I < n; ++I)
            scratch.y[I][0] = scratch.y0[I], scratch.y[I][1] = scratch.y1[I];
        Tensor<1, dim> w;
        for (unsigned int I = 0; I < n; ++I)
        {
          const Tensor<1, dim> z = y[I] - r;
          const double zs        = z * step;
          w += (N[I] * zs * zs) * z;
        }
        const Tensor<1, dim> c = -0.5 * (J_inv_step * w);
        // Outside the local regime keep the plain Newton direction.
        if (c.norm() < 0.5 * step.norm() && r * (step + c) < 0.5 * (r * step))
          step += c;
      }
      const double slope = r * step; // < 0: a descent direction
      // Line search for the Wolfe conditions along the Newton direction: enough
      // decrease of log Z, and the directional derivative r . step shrunk to
      // c2 |slope|. Sufficient decrease alone accepts steps that jump far past
      // the minimum along the line, which is what costs iterations from a cold
      // start at large gamma or near the boundary. phi(t) = log Z(mu + t step) is
      // convex, so the sign of phi' brackets its minimum and a secant on phi'
      // refines the step. noise: the rounding of log Z, below which a decrease
      // cannot be measured.
      const double noise = 32 * std::numeric_limits<double>::epsilon() *
                           (1 + std::abs(F) + mu.norm() * radius_over_h);
      double t = 1, t_lo = 0, t_hi = std::numeric_limits<double>::infinity();
      double d_lo = slope, d_hi = 0;
      for (unsigned int trial = 0;; ++trial)
      {
        mu_trial = mu + t * step;
        evaluate_2d_or(scratch, n, mu_trial, N, F_trial, r_trial, J_trial);
        ++scratch.evaluations;
        const double d_phi  = r_trial * step;
        const bool decrease = F_trial <= F + c1 * t * slope + noise;
        if ((decrease && std::abs(d_phi) <= -c2 * slope) || r_trial.norm() < newton_tol)
          break;
        if (trial == 60)
          report("line search failed");
        if (!decrease || d_phi > 0)
          t_hi = t, d_hi = d_phi;
        else
          t_lo = t, d_lo = d_phi;
        if (!std::isfinite(t_hi))
          t *= 4;
        else
        {
          const double width = t_hi - t_lo;
          const double secant =
              (d_hi > d_lo) ? t_lo - d_lo * width / (d_hi - d_lo) : t_lo + 0.5 * width;
          t = std::clamp(secant, t_lo + 0.01 * width, t_hi - 0.01 * width);
        }
      }
      mu = mu_trial, r = r_trial, J = J_trial, F = F_trial;
      ++it;
    }
    if (singular(J))
      report("singular Hessian");
    ++scratch.solves;
    scratch.iterations += it - cheap;
    scratch.cheap += cheap;
    scratch.max_iterations = std::max(scratch.max_iterations, it - cheap);
    return {mu, r, J};
  }

  /// grad N_I from the Hessian J, and the state kept for the next warm start. Arroyo &
  /// Ortiz's grad N_I = N_I (grad f_I - sum_J N_J grad f_J) is -N_I J^-1 (y_I - r) / h;
  /// the usual form drops r (zero at the exact multiplier), leaving sum grad N_I =
  /// -J^-1 r / h, large where J is small (near a node at large gamma). Keeping r, both
  /// gradient consistency conditions hold to rounding whatever the Newton residual.
  void gradients(ParticleStore<dim> &particles, const std::size_t p, const unsigned int n,
                 const double h, const Scratch &scratch, const double *N,
                 const Solution &solution, Tensor<1, dim> *gradN) const
  {
    const double inv_h         = 1 / h;
    const Tensor<2, dim> unit  = unit_symmetric_tensor<dim>();
    const Tensor<2, dim> J_inv = invert(solution.J);
    const Tensor<1, dim> &r    = solution.r;
    particles.lme_lambda[p]    = solution.mu * inv_h;
    particles.lme_position[p]  = particles.position[p];
    if (!support.is_graded())
    {
      if constexpr (dim == 2)
        for (unsigned int I = 0; I < n; ++I)
        {
          // J_inv (y_I - r) scaled by -N_I / h, in the Tensor operations' order.
          const double u = scratch.y0[I] - r[0], v = scratch.y1[I] - r[1];
          const double c = -N[I] * inv_h;
          gradN[I][0]    = c * (J_inv[0][0] * u + J_inv[0][1] * v);
          gradN[I][1]    = c * (J_inv[1][0] * u + J_inv[1][1] * v);
        }
      else
        for (unsigned int I = 0; I < n; ++I)
          gradN[I] = (-N[I] * inv_h) * (J_inv * (scratch.y[I] - r));
      particles.lme_lambda_rate[p] = (2 * gamma * unit - J_inv) * (inv_h * inv_h);
      return;
    }
    // Nodal beta_I = gamma w_I / h^2. With s = sum N_I w_I y_I and C = sum N_I w_I y_I
    // (x) y_I - r (x) s, keeping r(x, mu(x)) fixed gives the scaled multiplier's rate
    // M = d mu / d(x / h) = -J^-1 (I - 2 gamma C), and
    //   h grad N_I = N_I (-2 gamma w_I y_I + 2 gamma s + M^T (y_I - r)),
    // which sums to zero exactly and reproduces linear fields' gradients. With all
    // w_I = 1 it is the uniform form above.
    Tensor<1, dim> s;
    Tensor<2, dim> C;
    if constexpr (dim == 2)
    {
      // The Tensor operations below written out on the 2D offsets, in their order.
      const double *y0 = scratch.y0.data(), *y1 = scratch.y1.data();
      for (unsigned int I = 0; I < n; ++I)
      {
        const double c = N[I] * scratch.w[I], v0 = c * y0[I], v1 = c * y1[I];
        s[0] += v0, s[1] += v1;
        C[0][0] += v0 * y0[I], C[0][1] += v0 * y1[I];
        C[1][0] += v1 * y0[I], C[1][1] += v1 * y1[I];
      }
    }
    else
      for (unsigned int I = 0; I < n; ++I)
      {
        const Tensor<1, dim> v = (N[I] * scratch.w[I]) * scratch.y[I];
        s += v;
        C += outer_product(v, scratch.y[I]);
      }
    C -= outer_product(r, s);
    const Tensor<2, dim> M   = -(J_inv * (unit - (2 * gamma) * C));
    const Tensor<2, dim> Mt  = transpose(M);
    const Tensor<1, dim> g2s = (2 * gamma) * s;
    if constexpr (dim == 2)
      for (unsigned int I = 0; I < n; ++I)
      {
        const double a = -2 * gamma * scratch.w[I], c = N[I] * inv_h;
        const double u = scratch.y0[I] - r[0], v = scratch.y1[I] - r[1];
        gradN[I][0] = c * ((a * scratch.y0[I] + g2s[0]) + (Mt[0][0] * u + Mt[0][1] * v));
        gradN[I][1] = c * ((a * scratch.y1[I] + g2s[1]) + (Mt[1][0] * u + Mt[1][1] * v));
      }
    else
      for (unsigned int I = 0; I < n; ++I)
        gradN[I] = (N[I] * inv_h) * ((-2 * gamma * scratch.w[I]) * scratch.y[I] + g2s +
                                     Mt * (scratch.y[I] - r));
    particles.lme_lambda_rate[p] = M * (inv_h * inv_h);
  }

  /// Wolfe constants of the line search (sufficient decrease, curvature).
  static constexpr double c1 = 1e-4, c2 = 0.1;
  const double gamma;
  const double newton_tol;
  /// Largest |t| of a polynomial_step(): its relative error t^4 / 24 is below newton_tol.
  const double cheap_step_limit;
  const unsigned int max_iterations;
  const double radius_over_h;        ///< support radius R / h
  const lme_simd::Kernels2 &kernels; ///< the 2D passes, scalar or SIMD
  const LmeSupport<dim> support;     ///< which nodes hold a point

  mutable std::atomic<std::uint64_t> n_solves{0};
  mutable std::atomic<std::uint64_t> n_iterations{0};
  mutable std::atomic<std::uint64_t> n_evaluations{0};
  mutable std::atomic<std::uint64_t> n_cheap_steps{0};
  mutable std::atomic<unsigned int> max_iterations_seen{0};
};
} // namespace shape_functions
} // namespace lme_mpm

using lme_mpm::shape_functions::LME;
LME_MPM_REGISTER_SHAPE_FUNCTION(LME, "lme",
                                "local maximum-entropy approximants (Arroyo & Ortiz "
                                "2006): smooth, non-negative, tunable locality 'LME "
                                "gamma'; a Newton solve per particle.")
