#include <deal.II/base/multithread_info.h>

#include <lme_mpm/base/parallel.h>
#include <lme_mpm/particles/damage_form.h>
#include <lme_mpm/solver/grid_transfer.h>

#include <atomic>
#include <cmath>

namespace lme_mpm
{
namespace
{
/// The lowest of the indices offered, from any thread (a reproducible report).
void keep_lowest(std::atomic<std::size_t> &lowest, const std::size_t p)
{
  std::size_t cur = lowest.load();
  while (p < cur && !lowest.compare_exchange_weak(cur, p))
    ;
}

void raise_to(std::atomic<unsigned int> &m, const unsigned int v)
{
  unsigned int seen = m.load();
  while (v > seen && !m.compare_exchange_weak(seen, v))
  {
  }
}
} // namespace

template <int dim>
GridTransfer<dim>::GridTransfer(const BackgroundGrid<dim> &grid,
                                ParticleStore<dim> &particles)
    : grid(grid), particles(particles), n_threads(MultithreadInfo::n_threads())
{
}

template <int dim>
std::size_t GridTransfer<dim>::locate_and_sort()
{
  const std::size_t n = particles.size();
  std::atomic<std::size_t> lost{n};
  parallel::for_range(n,
                      [&](const std::size_t b, const std::size_t e)
                      {
                        std::array<unsigned int, dim> ijk;
                        for (std::size_t p = b; p < e; ++p)
                          if (grid.locate(particles.position[p], ijk))
                            particles.cell[p] = grid.cell_index(ijk);
                          else
                            keep_lowest(lost, p);
                      });
  if (lost.load() < n)
    return lost.load();
  const bool changed = particles.sort_by_cell(grid.n_cells());
  // The first sort puts the particles, made body by body, in cell order: not a step's.
  if (located_once)
    reordered += changed, ++sorts;
  located_once = true;
  return n;
}

template <int dim>
std::pair<unsigned int, unsigned int>
GridTransfer<dim>::support_reach(const std::size_t begin, const std::size_t end) const
{
  unsigned int below = 0, above = 0;
  with_rows(grid, conn,
            [&](const auto &rows)
            {
              for (std::size_t p = begin; p < end; ++p)
              {
                const unsigned int layer = grid.cell_layer(particles.cell[p]);
                const auto [first, last] = rows.first_and_last(p);
                const unsigned int lo    = grid.node_layer(first);
                const unsigned int hi    = grid.node_layer(last);
                below                    = std::max(below, layer > lo ? layer - lo : 0u);
                above                    = std::max(above, hi > layer ? hi - layer : 0u);
              }
            });
  return {below, above};
}

template <int dim>
void GridTransfer<dim>::scatter_particles(const std::size_t b, const std::size_t e)
{
  with_rows(grid, conn, [&](const auto &rows) { scatter_particles(rows, b, e); });
}

template <int dim>
template <class Rows>
void GridTransfer<dim>::scatter_particles(const Rows &rows, const std::size_t b,
                                          const std::size_t e)
{
  for (std::size_t p = b; p < e; ++p)
  {
    const double m          = particles.mass[p];
    const Tensor<1, dim> mv = m * particles.velocity[p],
                         ma = m * particles.acceleration[p];
    rows.visit(p,
               [&](const unsigned int I, const double N, const Tensor<1, dim> &)
               {
                 fields.mass[I] += N * m;
                 fields.momentum[I] += N * mv;
                 fields.mass_acceleration[I] += N * ma;
               });
  }
}

template <int dim>
void GridTransfer<dim>::particles_to_grid(
    const ShapeFunction<dim> &shape_function,
    const std::vector<unsigned int> &extra_nodes,
    const std::function<void(std::size_t, std::size_t)> &remap, const bool full_rows)
{
  // Each chunk gets its shape functions and scatters them while they are in cache,
  // in slabs sized by the reach of the supports so far. A chunk whose supports reach
  // further does not scatter (so no two threads can meet on a node); the reach is
  // then widened and the whole transfer repeated, which happens on the first step
  // and where supports grow. The order depends on the particles only, not on the
  // threads.
  fields.clear(extra_nodes);
  // Rows kept as their factors where nothing but the transfers reads them: fewer
  // bytes written here and read by every pass after (doc/performance.md).
  const unsigned int width = shape_function.factor_width();
  if (!full_rows && shape_function.rows_are_cell_hats())
    conn.resize_cells(particles.size(), particles.position);
  else if (!full_rows && (width == 2 || width == 4))
    conn.resize_factors(particles.size(), width);
  else
    conn.resize(particles.size(), shape_function.max_nodes_per_particle());
  const unsigned int below = slab_below, above = slab_above;
  std::atomic<unsigned int> reach_below{below}, reach_above{above};
  scatter_chunks(
      [&](const std::size_t b, const std::size_t e)
      {
        shape_function.compute(particles, b, e, conn);
        const auto [chunk_below, chunk_above] = support_reach(b, e);
        remap(b, e);
        raise_to(reach_below, chunk_below);
        raise_to(reach_above, chunk_above);
        return chunk_below <= below && chunk_above <= above;
      },
      [&](const std::size_t b, const std::size_t e) { scatter_particles(b, e); });
  unsigned int new_below = reach_below.load(), new_above = reach_above.load();
  if (ranks)
  {
    new_below = static_cast<unsigned int>(ranks->max(new_below));
    new_above = static_cast<unsigned int>(ranks->max(new_above));
  }
  if (new_below > below || new_above > above)
  {
    slab_below = std::max(below, new_below), slab_above = std::max(above, new_above);
    fields.collect_active();
    fields.clear(extra_nodes);
    scatter_chunks([&](const std::size_t b, const std::size_t e)
                   { scatter_particles(b, e); });
  }
  fields.collect_active();
}

template <int dim>
void GridTransfer<dim>::predict_rates(const ExplicitNewmark &newmark, const double dt,
                                      const double mass_tolerance)
{
  fields.for_active(
      [&](const unsigned int I)
      {
        fields.rate[I] = fields.mass[I] > mass_tolerance
                             ? newmark.displacement_rate(
                                   fields.momentum[I] / fields.mass[I],
                                   fields.mass_acceleration[I] / fields.mass[I], dt)
                             : Tensor<1, dim>();
      });
}

template <int dim>
void GridTransfer<dim>::strain_increments(const std::size_t b, const std::size_t e,
                                          const double dt)
{
  with_rows(grid, conn, [&](const auto &rows) { strain_increments(rows, b, e, dt); });
}

template <int dim>
template <class Rows>
void GridTransfer<dim>::strain_increments(const Rows &rows, const std::size_t b,
                                          const std::size_t e, const double dt)
{
  for (std::size_t p = b; p < e; ++p)
  {
    Tensor<2, dim> grad_v;
    rows.visit(p, [&](const unsigned int I, const double, const Tensor<1, dim> &grad_N)
               { grad_v += outer_product(fields.rate[I], grad_N); });
    const SymmetricTensor<2, dim> de = dt * symmetrize(grad_v);
    particles.strain_increment[p]    = de;
    particles.strain[p] += de;
    particles.density[p] /= (1 + trace(de));
    particles.volume[p] = particles.mass[p] / particles.density[p];
  }
}

template <int dim>
void GridTransfer<dim>::forces(const std::size_t b, const std::size_t e,
                               const Tensor<1, dim> &body_force)
{
  with_rows(grid, conn, [&](const auto &rows) { forces(rows, b, e, body_force); });
}

template <int dim>
template <class Rows>
void GridTransfer<dim>::forces(const Rows &rows, const std::size_t b, const std::size_t e,
                               const Tensor<1, dim> &body_force)
{
  const bool gravity = body_force.norm_square() > 0;
  for (std::size_t p = b; p < e; ++p)
  {
    // A full tensor: the symmetric one's element access costs more per node.
    const Tensor<2, dim> s =
        has_crack_normal(particles, p)
            ? Tensor<2, dim>(particles.initial_volume[p] * effective_stress(particles, p))
            : Tensor<2, dim>((stress_factor(particles, p) * particles.initial_volume[p]) *
                             particles.stress[p]);
    if (gravity)
    {
      const Tensor<1, dim> g = particles.mass[p] * body_force;
      rows.visit(p,
                 [&](const unsigned int I, const double N, const Tensor<1, dim> &grad_N)
                 { fields.force[I] += N * g - s * grad_N; });
    }
    else
      rows.visit(p, [&](const unsigned int I, const double, const Tensor<1, dim> &grad_N)
                 { fields.force[I] -= s * grad_N; });
  }
}

template <int dim>
void GridTransfer<dim>::accelerations(const double mass_tolerance)
{
  fields.for_active(
      [&](const unsigned int I)
      {
        fields.acceleration[I] = fields.mass[I] > mass_tolerance
                                     ? fields.force[I] / fields.mass[I]
                                     : Tensor<1, dim>();
      });
}

template <int dim>
double GridTransfer<dim>::grid_to_particles(const ExplicitNewmark &newmark,
                                            const double dt,
                                            const Tensor<1, dim> &body_force,
                                            const double max_move, std::size_t &bad,
                                            double &max_speed)
{
  const std::size_t n = particles.size();
  std::atomic<std::size_t> first_bad{n};
  std::atomic<double> fastest{0.0};
  const bool xpic = xpic_order > 0;
  // A constant body force does work m b . dx over the step's displacement exactly.
  const auto update = [&](const std::size_t b, const std::size_t e)
  {
    double pw = 0, v2 = 0;
    with_rows(
        grid, conn,
        [&](const auto &rows)
        {
          for (std::size_t p = b; p < e; ++p)
          {
            // Ghosts (copies of another rank's particles) are not updated: the
            // exchange that ends the step writes their owners' values over them, and
            // nothing reads them before it.
            if (particles.ghost[p])
              continue;
            // The interpolations in one walk over the row, each summed in its order.
            // The rates are those the strains were taken from (nothing changes them
            // after the predictor): interpolated here, not stored per particle.
            Tensor<1, dim> a, v_start, rate;
            // Two walks, one chosen per particle: a test of xpic inside the walk
            // made this pass twice as slow (2D B-splines).
            if (xpic)
              rows.visit(p,
                         [&](const unsigned int I, const double N, const Tensor<1, dim> &)
                         {
                           a += N * fields.acceleration[I];
                           v_start += N * start_velocity[I];
                           rate += N * fields.rate[I];
                         });
            else
              rows.visit(p,
                         [&](const unsigned int I, const double N, const Tensor<1, dim> &)
                         {
                           a += N * fields.acceleration[I];
                           rate += N * fields.rate[I];
                         });
            const Tensor<1, dim> v0 = xpic ? v_start : particles.velocity[p];
            particles.velocity[p] =
                newmark.corrected_velocity(v0, particles.acceleration[p], a, dt);
            particles.acceleration[p]      = a;
            const Tensor<1, dim> increment = dt * rate;
            particles.position[p] += increment;
            if (prescribed_body.empty() || !prescribed_body[particles.body_id[p]])
              pw += particles.mass[p] * (body_force * increment);
            v2                = std::max(v2, particles.velocity[p].norm_square());
            const double move = increment.norm();
            // Leaving the grid is caught here, where the guard's flag rides on the
            // step's one reduction, not at the next step's search of cells.
            if (!(move < max_move) ||
                !std::isfinite(particles.velocity[p].norm_square()) ||
                !(particles.density[p] > 0) || !grid.inside(particles.position[p]))
              keep_lowest(first_bad, p);
          }
        });
    double seen = fastest.load();
    while (v2 > seen && !fastest.compare_exchange_weak(seen, v2))
    {
    }
    return pw;
  };
  // Without a body force every term of the work is zero: the particles need not go in
  // the blocks of a sum that is independent of the threads, which are few and uneven
  // for a few thousand particles.
  double body_work = 0;
  if (body_force.norm_square() == 0)
    parallel::for_range(n, update);
  else
    body_work = parallel::deterministic_sum<double>(n, update);
  bad       = first_bad.load();
  max_speed = std::sqrt(fastest.load());
  return body_work;
}

template <int dim>
void GridTransfer<dim>::interpolate_accelerations()
{
  parallel::for_range(particles.size(),
                      [&](const std::size_t b, const std::size_t e)
                      {
                        for (std::size_t p = b; p < e; ++p)
                          particles.acceleration[p] = interpolate(fields.acceleration, p);
                      });
}

template <int dim>
void GridTransfer<dim>::apply_consistent_mass(const std::vector<Tensor<1, dim>> &x,
                                              std::vector<Tensor<1, dim>> &Mx)
{
  // (M_C x)_I = sum_p N_Ip m_p sum_J N_Jp x_J: interpolate, then scatter back.
  const std::size_t n = particles.size();
  particle_scratch.resize(n);
  parallel::for_range(n,
                      [&](const std::size_t b, const std::size_t e)
                      {
                        for (std::size_t p = b; p < e; ++p)
                          particle_scratch[p] = particles.mass[p] * interpolate(x, p);
                      });
  for (const unsigned int I : fields.active)
    Mx[I] = Tensor<1, dim>();
  with_rows(grid, conn,
            [&](const auto &rows)
            {
              scatter(
                  [&](const std::size_t p)
                  {
                    rows.visit(p, [&](const unsigned int I, const double N,
                                      const Tensor<1, dim> &)
                               { Mx[I] += N * particle_scratch[p]; });
                  });
            });
}

template class GridTransfer<2>;
template class GridTransfer<3>;
} // namespace lme_mpm
