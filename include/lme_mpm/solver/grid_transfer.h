#ifndef LME_MPM_SOLVER_GRID_TRANSFER_H
#define LME_MPM_SOLVER_GRID_TRANSFER_H

#include <deal.II/base/parallel.h>
#include <deal.II/base/tensor.h>

#include <tbb/parallel_pipeline.h>

#include <lme_mpm/base/rank_reductions.h>
#include <lme_mpm/grid/background_grid.h>
#include <lme_mpm/grid/nodal_fields.h>
#include <lme_mpm/particles/particle_store.h>
#include <lme_mpm/shape_functions/shape_function.h>
#include <lme_mpm/shape_functions/tensor_product.h>
#include <lme_mpm/solver/explicit_newmark.h>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

namespace lme_mpm
{
/**
 * The transfers between particles and grid: the connectivity (shape functions) of
 * every particle, the nodal fields, and the particle-to-grid scatter, whose sums do
 * not depend on the thread count. Particles are sorted by cell and cut into slabs of
 * cell layers as wide as the supports reach; slabs of one colour touch disjoint
 * nodes and run concurrently, each in particle order (two colours in turn).
 *
 * The kernels (strain increments, internal forces, the Newmark corrector) are
 * separate calls so that the solver can fuse them chunk by chunk while a chunk's
 * connectivity is in cache.
 */
template <int dim>
class GridTransfer
{
public:
  /// Small enough for a chunk's connectivity to stay in the L2 cache.
  static constexpr std::size_t chunk = 256;

  GridTransfer(const BackgroundGrid<dim> &grid, ParticleStore<dim> &particles);

  NodalFields<dim> &nodes() { return fields; }
  const NodalFields<dim> &nodes() const { return fields; }
  /**
   * The rows of the step. Where only the transfers read them they may be kept as
   * their factors (Connectivity), with `nodes`, `N` and `grad_N` empty: a part that
   * reads the full rows asks for them (particles_to_grid()'s @p full_rows).
   */
  const Connectivity<dim> &connectivity() const { return conn; }
  /// The displacement rate at particle @p p (after the predictor).
  Tensor<1, dim> rate_at(const std::size_t p) const
  {
    return interpolate(fields.rate, p);
  }
  Connectivity<dim> &connectivity() { return conn; }
  /// Threads the scatter runs on (fixed when the transfer is built).
  unsigned int threads() const { return n_threads; }

  /**
   * Finds every particle's cell and sorts the particles by cell. Returns the lowest
   * index of a particle outside the grid (reproducible), or the number of particles.
   */
  std::size_t locate_and_sort();
  /// How many locate_and_sort() calls changed the particles' order, of how many,
  /// the first call (since the run or its resume started) left out: what a cache of
  /// particle indices kept across steps would have to follow.
  std::pair<std::uint64_t, std::uint64_t> reorders() const { return {reordered, sorts}; }

  /**
   * Computes the shape functions chunk by chunk, lets @p remap(begin, end) redirect
   * particle-node pairs to other fields of a node (explicit cracks), and scatters
   * mass, momentum and mass-weighted acceleration to the nodal fields, clearing first
   * what the last step wrote and the fields of @p extra_nodes.
   */
  void particles_to_grid(const ShapeFunction<dim> &shape_function,
                         const std::vector<unsigned int> &extra_nodes,
                         const std::function<void(std::size_t, std::size_t)> &remap,
                         bool full_rows = true);

  /// Displacement rate w = v + dt/2 a on every field with mass.
  void predict_rates(const ExplicitNewmark &newmark, double dt, double mass_tolerance);
  /// Strain increment, strain, density and volume of [begin, end) from the nodal
  /// rates.
  void strain_increments(std::size_t begin, std::size_t end, double dt);
  /// Internal forces (damaged stress) and body force of [begin, end) on the nodes.
  void forces(std::size_t begin, std::size_t end, const Tensor<1, dim> &body_force);
  /// a = f / m on every field with mass.
  void accelerations(double mass_tolerance);
  /**
   * Newmark corrector on the particles, their position update and the sanity
   * checks. Returns the work of the body force over the step; @p bad receives the
   * lowest index of a particle that moved more than @p max_move, or whose velocity
   * is not finite or density not positive (the number of particles if none), and
   * @p max_speed the largest particle speed on this rank.
   */
  double grid_to_particles(const ExplicitNewmark &newmark, double dt,
                           const Tensor<1, dim> &body_force, double max_move,
                           std::size_t &bad, double &max_speed);
  /**
   * The particle update of XPIC(@p order) (Hammerquist & Nairn 2017): the next
   * grid_to_particles() starts each particle from the start-of-step grid velocity
   * v* = sum_{k<order} (I - M_L^-1 M_C)^k v_g interpolated to it, in place of its own
   * velocity, so the part of the particle velocities the grid cannot represent is
   * dropped while the grid-representable part is kept to the order's accuracy
   * (order 1 is PIC). @p constrain imposes the constraints' velocities on each
   * term. Order 0 restores the FLIP update.
   */
  template <class Constrain>
  void extend_start_velocity(const unsigned int order, const double mass_tolerance,
                             const Constrain &constrain)
  {
    xpic_order = order;
    if (order == 0)
      return;
    start_velocity.resize(fields.mass.size());
    term.resize(fields.mass.size());
    fields.for_active(
        [&](const unsigned int I)
        {
          term[I] = fields.mass[I] > mass_tolerance ? fields.momentum[I] / fields.mass[I]
                                                    : Tensor<1, dim>();
        });
    constrain(term);
    fields.for_active([&](const unsigned int I) { start_velocity[I] = term[I]; });
    for (unsigned int k = 1; k < order; ++k)
    {
      apply_consistent_mass(term, fields.scratch);
      fields.for_active(
          [&](const unsigned int I)
          {
            if (fields.mass[I] > mass_tolerance)
              term[I] -= fields.scratch[I] / fields.mass[I];
          });
      constrain(term);
      fields.for_active([&](const unsigned int I) { start_velocity[I] += term[I]; });
    }
  }

  /**
   * Distributed runs: the supports' reach in cell layers is made the same on every
   * MPI rank (the largest), as the slabs fix the order in which a node sums its
   * particles, which must not depend on which particles a rank holds.
   */
  void set_ranks(const RankReductions &r) { ranks = &r; }

  /// Bodies (flag per body index) whose motion is prescribed: the body force does no
  /// work on them.
  void set_prescribed_bodies(const std::vector<std::uint8_t> &flags)
  {
    prescribed_body = flags;
  }

  /// The particles' accelerations from the nodal ones (no other update): the start
  /// of the scheme.
  void interpolate_accelerations();

  /// Mx = M_C x with the consistent mass matrix (two transfers, no matrix stored).
  void apply_consistent_mass(const std::vector<Tensor<1, dim>> &x,
                             std::vector<Tensor<1, dim>> &Mx);
  /**
   * @p n Jacobi corrections of x on M_C x = rhs preconditioned by the lumped mass,
   * starting from the lumped solution; @p constrain(x) re-imposes the constraints.
   */
  template <class Constrain>
  void correct_towards_consistent_mass(std::vector<Tensor<1, dim>> &x,
                                       const std::vector<Tensor<1, dim>> &rhs,
                                       unsigned int n, double mass_tolerance,
                                       const Constrain &constrain)
  {
    for (unsigned int k = 0; k < n; ++k)
    {
      apply_consistent_mass(x, fields.scratch);
      fields.for_active(
          [&](const unsigned int I)
          {
            if (fields.mass[I] > mass_tolerance)
              x[I] += (rhs[I] - fields.scratch[I]) / fields.mass[I];
          });
      constrain(x);
    }
  }

  /// Calls f(p) for every particle in the scatter's order (see the class).
  template <class F>
  void scatter(const F &f) const
  {
    scatter_chunks(
        [&](const std::size_t b, const std::size_t e)
        {
          for (std::size_t p = b; p < e; ++p)
            f(p);
        });
  }

  /// The scatter's order, handing f(begin, end) chunks of at most `chunk` particles.
  template <class F>
  void scatter_chunks(const F &f) const
  {
    for_slabs(
        [&](const std::size_t b, const std::size_t e)
        {
          for (std::size_t c = b; c < e; c += chunk)
            f(c, std::min(e, c + chunk));
        });
  }

  /// The slabs, as f(begin, end) of their particles: those of one colour concurrently,
  /// the two colours in turn.
  template <class F>
  void for_slabs(const F &f) const
  {
    // Slabs of slab_below + slab_above cell layers: every scattering particle's
    // support lies within slab_below layers below and slab_above above its own, so
    // slabs of one colour touch disjoint nodes.
    const auto &offsets         = particles.cell_offsets();
    const unsigned int cpl      = grid.cells_per_layer();
    const unsigned int n_layers = grid.n_cells_in(dim - 1);
    const unsigned int w        = std::max(1u, slab_below + slab_above);
    const unsigned int n_slabs  = (n_layers + w - 1) / w;
    auto run_slab               = [&](const unsigned int s)
    { f(offsets[s * w * cpl], offsets[std::min((s + 1) * w, n_layers) * cpl]); };
    for (unsigned int colour = 0; colour < 2; ++colour)
    {
      const unsigned int n_this = (n_slabs + 1 - colour) / 2;
      if (n_threads == 1 || n_this < 2)
        for (unsigned int i = 0; i < n_this; ++i)
          run_slab(colour + 2 * i);
      else
        dealii::parallel::apply_to_subranges(
            0u, n_this,
            [&](const unsigned int i0, const unsigned int i1)
            {
              for (unsigned int i = i0; i < i1; ++i)
                run_slab(colour + 2 * i);
            },
            1);
    }
  }

  /**
   * scatter_chunks() with each chunk's work in two parts: @p prepare(begin, end),
   * which writes to its own particles only and returns whether the chunk may scatter,
   * and then @p scatter(begin, end) if it may. The scatters keep the order of
   * scatter_chunks(), so the sums their nodes receive are the same to the bit; the
   * preparations of a slab's chunks may run on any thread, ahead of its scatter.
   * A slab costlier than the others (particles whose shape functions take longer)
   * then no longer holds the other threads waiting at the end of its colour.
   */
  template <class Prepare, class Scatter>
  void scatter_chunks(const Prepare &prepare, const Scatter &scatter) const
  {
    if (n_threads == 1)
    {
      scatter_chunks(
          [&](const std::size_t b, const std::size_t e)
          {
            if (prepare(b, e))
              scatter(b, e);
          });
      return;
    }
    for_slabs(
        [&](const std::size_t b, const std::size_t e)
        {
          // The chunks of the slab through a pipeline: prepared on any thread (at most
          // two per thread ahead), scattered one at a time in the slab's order.
          struct Chunk
          {
            std::size_t begin, end;
            bool scatters;
          };
          std::size_t next = b;
          tbb::parallel_pipeline(
              2 * n_threads,
              tbb::make_filter<void, Chunk>(
                  tbb::filter_mode::serial_in_order,
                  [&](tbb::flow_control &control)
                  {
                    if (next >= e)
                    {
                      control.stop();
                      return Chunk{e, e, false};
                    }
                    const Chunk c{next, std::min(e, next + chunk), false};
                    next = c.end;
                    return c;
                  }) &
                  tbb::make_filter<Chunk, Chunk>(tbb::filter_mode::parallel,
                                                 [&](Chunk c)
                                                 {
                                                   c.scatters = prepare(c.begin, c.end);
                                                   return c;
                                                 }) &
                  tbb::make_filter<Chunk, void>(tbb::filter_mode::serial_in_order,
                                                [&](const Chunk &c)
                                                {
                                                  if (c.scatters)
                                                    scatter(c.begin, c.end);
                                                }));
        });
  }

  template <class Archive>
  void serialize(Archive &ar)
  {
    ar(slab_below, slab_above);
  }

private:
  /// sum_I N_Ip x_I at particle p of a nodal vector field (same order of sums in every
  /// interpolation, so they agree to the bit).
  Tensor<1, dim> interpolate(const std::vector<Tensor<1, dim>> &x,
                             const std::size_t p) const
  {
    Tensor<1, dim> xp;
    with_rows(grid, conn, [&](const auto &rows) { xp = interpolate(rows, x, p); });
    return xp;
  }
  template <class Rows>
  static Tensor<1, dim>
  interpolate(const Rows &rows, const std::vector<Tensor<1, dim>> &x, const std::size_t p)
  {
    Tensor<1, dim> xp;
    rows.visit(p, [&](const unsigned int I, const double N, const Tensor<1, dim> &)
               { xp += N * x[I]; });
    return xp;
  }
  /// How many cell layers the supports of [begin, end) reach below and above their
  /// particles' layers.
  std::pair<unsigned int, unsigned int> support_reach(std::size_t begin,
                                                      std::size_t end) const;
  /// Mass, momentum and mass-weighted acceleration of [begin, end) on the nodes.
  void scatter_particles(std::size_t begin, std::size_t end);
  template <class Rows>
  void scatter_particles(const Rows &rows, std::size_t begin, std::size_t end);
  template <class Rows>
  void strain_increments(const Rows &rows, std::size_t begin, std::size_t end, double dt);
  template <class Rows>
  void forces(const Rows &rows, std::size_t begin, std::size_t end,
              const Tensor<1, dim> &body_force);

  const BackgroundGrid<dim> &grid;
  ParticleStore<dim> &particles;
  const unsigned int n_threads;
  std::uint64_t sorts = 0, reordered = 0;
  bool located_once = false;
  Connectivity<dim> conn;
  NodalFields<dim> fields;
  // How many cell layers the supports have reached below and above their particles'
  // layers so far: the slab width of the scatter.
  unsigned int slab_below = 0, slab_above = 0;
  const RankReductions *ranks = nullptr;
  std::vector<std::uint8_t> prescribed_body;
  /// Per particle: scratch of the consistent-mass product.
  std::vector<Tensor<1, dim>> particle_scratch;
  /// XPIC: its order (0: FLIP), the nodal start velocity v* and a term of its series.
  unsigned int xpic_order = 0;
  std::vector<Tensor<1, dim>> start_velocity, term;
};
} // namespace lme_mpm

#endif
