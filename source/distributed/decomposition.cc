#include <deal.II/distributed/tria.h>
#include <deal.II/grid/grid_generator.h>

#include <lme_mpm/base/input.h>
#include <lme_mpm/distributed/decomposition.h>

#include "particle_messages.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace lme_mpm
{
namespace
{
unsigned long long all_reduce(MPI_Comm comm, const unsigned int size,
                              const unsigned long long v, MPI_Op op)
{
  if (size == 1)
    return v;
  unsigned long long result = 0;
  MPI_Allreduce(&v, &result, 1, MPI_UNSIGNED_LONG_LONG, op, comm);
  return result;
}
} // namespace

template <int dim>
Decomposition<dim>::Decomposition(MPI_Comm comm) : comm(comm)
{
  // Without MPI started (a test program, a library user), one rank.
  if (Utilities::MPI::job_supports_mpi())
  {
    size    = Utilities::MPI::n_mpi_processes(comm);
    my_rank = Utilities::MPI::this_mpi_process(comm);
  }
}

template <int dim>
std::size_t Decomposition<dim>::n_owned(const ParticleStore<dim> &particles)
{
  std::size_t n = 0;
  for (const std::uint8_t g : particles.ghost)
    n += (g == 0);
  return n;
}

template <int dim>
void Decomposition<dim>::partition(const BackgroundGrid<dim> &g, const HaloReach &reach)
{
  grid = &g;
  if (size == 1)
    return;
  const unsigned int n_cells = g.n_cells();
  halo                       = std::make_unique<HaloCells<dim>>(g, reach);

  // p4est partitions the grid's cells (one coarse cell each, in the order deal.II
  // gives them for p4est, which keeps a rank's cells together).
  {
    parallel::distributed::Triangulation<dim> tria(comm);
    std::vector<std::vector<double>> steps(dim);
    for (unsigned int d = 0; d < dim; ++d)
    {
      const auto &c = g.coordinates(d);
      for (std::size_t i = 0; i + 1 < c.size(); ++i)
        steps[d].push_back(c[i + 1] - c[i]);
    }
    GridGenerator::subdivided_hyper_rectangle(tria, steps, g.lower_corner(),
                                              g.upper_corner());
    std::vector<int> owner(n_cells, -1);
    for (const auto &cell : tria.active_cell_iterators())
      if (cell->is_locally_owned())
      {
        std::array<unsigned int, dim> ijk;
        AssertThrow(g.locate(cell->center(), ijk), ExcInternalError());
        owner[g.cell_index(ijk)] = static_cast<int>(my_rank);
      }
    MPI_Allreduce(MPI_IN_PLACE, owner.data(), static_cast<int>(n_cells), MPI_INT, MPI_MAX,
                  comm);
    cell_owner.assign(owner.begin(), owner.end());
    for (const int o : owner)
      AssertThrow(o >= 0, ExcInternalError());
  }

  std::vector<std::uint8_t> mine(n_cells);
  for (unsigned int c = 0; c < n_cells; ++c)
    mine[c] = cell_owner[c] == my_rank;
  const auto around_mine = halo->reached(mine);
  in_halo.assign(n_cells, 0);
  owned_cell_count = halo_cell_count = 0;
  for (unsigned int c = 0; c < n_cells; ++c)
  {
    in_halo[c] = around_mine[c] && !mine[c];
    owned_cell_count += mine[c];
    halo_cell_count += in_halo[c];
  }

  // Which ranks hold each of my cells in their halo.
  std::vector<std::vector<std::uint32_t>> needs(n_cells);
  for (unsigned int r = 0; r < size; ++r)
    if (r != my_rank)
    {
      std::vector<std::uint8_t> theirs(n_cells);
      for (unsigned int c = 0; c < n_cells; ++c)
        theirs[c] = cell_owner[c] == r;
      const auto around = halo->reached(theirs);
      for (unsigned int c = 0; c < n_cells; ++c)
        if (mine[c] && around[c])
          needs[c].push_back(r);
    }
  ghost_offsets.assign(n_cells + 1, 0);
  ghost_ranks.clear();
  for (unsigned int c = 0; c < n_cells; ++c)
  {
    ghost_ranks.insert(ghost_ranks.end(), needs[c].begin(), needs[c].end());
    ghost_offsets[c + 1] = ghost_ranks.size();
  }

  node_owned.assign(g.n_nodes(), 0);
  for (unsigned int n = 0; n < g.n_nodes(); ++n)
  {
    std::array<unsigned int, dim> ijk;
    unsigned int rest = n;
    for (int d = dim - 1; d >= 0; --d)
    {
      ijk[d] = rest / g.node_stride(d);
      rest -= ijk[d] * g.node_stride(d);
      ijk[d] = std::min(ijk[d], g.n_cells_in(d) - 1);
    }
    node_owned[n] = cell_owner[g.cell_index(ijk)] == my_rank;
  }
}

template <int dim>
void Decomposition<dim>::distribute(ParticleStore<dim> &particles) const
{
  if (size == 1)
    return;
  const std::size_t n = particles.size();
  std::vector<std::uint8_t> keep(n, 0);
  for (std::size_t p = 0; p < n; ++p)
  {
    std::array<unsigned int, dim> ijk;
    AssertThrow(grid->locate(particles.position[p], ijk), ExcInternalError());
    const unsigned int c = grid->cell_index(ijk);
    particles.ghost[p]   = cell_owner[c] != my_rank;
    keep[p]              = cell_owner[c] == my_rank || in_halo[c];
  }
  particle_messages::compact(particles, keep);
  particles.mark_reordered();
}

template <int dim>
void Decomposition<dim>::exchange(ParticleStore<dim> &particles)
{
  if (size == 1)
    return;
  constexpr unsigned int off_grid = ~0u;
  const auto cell_of              = [&](const std::size_t p)
  {
    std::array<unsigned int, dim> ijk;
    return grid->locate(particles.position[p], ijk) ? grid->cell_index(ijk) : off_grid;
  };
  const std::size_t n = particles.size();
  // keep: the owned particles that stay here; cells: where each of them lies (each
  // particle is located once).
  std::vector<std::uint8_t> keep(n, 0);
  std::vector<unsigned int> cells(n, off_grid);
  out.resize(size);
  for (auto &o : out)
    o.clear();
  bool left = false;
  for (std::size_t p = 0; p < n; ++p)
  {
    if (particles.ghost[p])
      continue;
    const unsigned int c = cell_of(p);
    // Off the grid: kept, and the next step stops the run and names it.
    if (c == off_grid || cell_owner[c] == my_rank)
      keep[p] = 1, cells[p] = c;
    else
    {
      particle_messages::pack(particles, p, out[cell_owner[c]]);
      left = true;
    }
  }
  particle_messages::all_to_all(comm, out, send_buffer, arrived_buffer);
  const std::vector<char> &arrived = arrived_buffer;
  const bool owned_stay            = !left && arrived.empty();
  if (!owned_stay)
  {
    particle_messages::compact(particles, keep);
    std::size_t kept = 0;
    for (std::size_t p = 0; p < n; ++p)
      if (keep[p])
        cells[kept++] = cells[p];
    cells.resize(kept);
    particle_messages::unpack(arrived, particles, 0);
    for (std::size_t p = cells.size(); p < particles.size(); ++p)
      cells.push_back(cell_of(p));
    keep.assign(particles.size(), 1);
  }

  // Ghosts afresh: every owned particle to the ranks whose halo holds its cell.
  for (auto &o : out)
    o.clear();
  for (std::size_t p = 0; p < particles.size(); ++p)
    if (keep[p] && cells[p] != off_grid)
      for (std::uint32_t k = ghost_offsets[cells[p]]; k < ghost_offsets[cells[p] + 1];
           ++k)
        particle_messages::pack(particles, p, out[ghost_ranks[k]]);
  particle_messages::all_to_all(comm, out, send_buffer, ghost_buffer);
  const std::vector<char> &ghosts = ghost_buffer;
  // Where no particle came or went and the halo holds the same particles as before
  // (most steps), the ghosts are written over in their slots: the store keeps its
  // order, and the next sort finds it sorted unless a particle changed cells. The
  // order after the sort is that of appending them (it depends on the particles
  // only), so this changes no sum.
  if (owned_stay && particle_messages::refill_ghosts(ghosts, particles, ghost_slots))
    return;
  if (owned_stay)
    particle_messages::compact(particles, keep);
  particle_messages::unpack(ghosts, particles, 1);
  particles.mark_reordered();
}

template <int dim>
void Decomposition<dim>::gather(const ParticleStore<dim> &particles,
                                ParticleStore<dim> &all) const
{
  all.resize(0);
  all.keep_state(particles.kept_state());
  std::vector<char> &mine = gather_mine;
  mine.clear();
  for (std::size_t p = 0; p < particles.size(); ++p)
    if (!particles.ghost[p])
      particle_messages::pack(particles, p, mine);
  int count = static_cast<int>(mine.size());
  std::vector<int> counts(size), at(size);
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
  const std::size_t total = particle_messages::displacements(counts, at);
  AssertThrow(total < std::size_t(std::numeric_limits<int>::max()),
              ExcMessage("the particles gathered for output exceed 2 GB: write less "
                         "often, or run fewer particles per job"));
  std::vector<char> &received = gather_received;
  received.resize(my_rank == 0 ? total : 0);
  MPI_Gatherv(mine.data(), count, MPI_CHAR, received.data(), counts.data(), at.data(),
              MPI_CHAR, 0, comm);
  if (my_rank != 0)
    return;
  particle_messages::unpack(received, all, 0);
  // In the order one rank holds them at output time: by the cell of the last sort,
  // then by id (so every sum over them is added as on one rank).
  all.sort_by_cell(grid->n_cells());
  all.mark_reordered();
}

template <int dim>
void Decomposition<dim>::gather_failed(const ParticleStore<dim> &particles,
                                       const double reach, ParticleStore<dim> &view) const
{
  view.resize(0);
  view.keep_state(particles.kept_state());
  // The cells within reach of a failed particle here (owned or ghost: a failed
  // particle of another rank near this one's cells is among the ghosts); their owned
  // particles go to every rank. Intact ones a little farther do not change growth.
  std::vector<std::uint8_t> cells(grid->n_cells(), 0);
  bool any = false;
  std::array<unsigned int, dim> ijk;
  for (std::size_t p = 0; p < particles.size(); ++p)
    if (particles.failed[p] && grid->locate(particles.position[p], ijk))
      cells[grid->cell_index(ijk)] = 1, any = true;
  std::vector<char> mine;
  if (any)
  {
    cells = halo->dilate(cells, halo->cells_within(reach));
    for (std::size_t p = 0; p < particles.size(); ++p)
      if (!particles.ghost[p] && grid->locate(particles.position[p], ijk) &&
          cells[grid->cell_index(ijk)])
        particle_messages::pack(particles, p, mine);
  }
  if (size == 1)
  {
    particle_messages::unpack(mine, view, 0);
  }
  else
  {
    const std::vector<std::vector<char>> everyone =
        Utilities::MPI::all_gather(comm, mine);
    for (const auto &piece : everyone)
      particle_messages::unpack(piece, view, 0);
  }
  view.sort_by_cell(grid->n_cells());
}

template <int dim>
double Decomposition<dim>::sum(const double v) const
{
  return size == 1 ? v : Utilities::MPI::sum(v, comm);
}

template <int dim>
void Decomposition<dim>::sum(std::vector<double> &v) const
{
  if (size > 1)
    MPI_Allreduce(MPI_IN_PLACE, v.data(), static_cast<int>(v.size()), MPI_DOUBLE, MPI_SUM,
                  comm);
}

template <int dim>
double Decomposition<dim>::max(const double v) const
{
  return size == 1 ? v : Utilities::MPI::max(v, comm);
}

template <int dim>
void Decomposition<dim>::max(std::vector<double> &v) const
{
  if (size > 1)
    MPI_Allreduce(MPI_IN_PLACE, v.data(), static_cast<int>(v.size()), MPI_DOUBLE, MPI_MAX,
                  comm);
}

template <int dim>
unsigned long long Decomposition<dim>::sum(const unsigned long long v) const
{
  return all_reduce(comm, size, v, MPI_SUM);
}

template <int dim>
unsigned long long Decomposition<dim>::min(const unsigned long long v) const
{
  return all_reduce(comm, size, v, MPI_MIN);
}

template <int dim>
std::vector<double> Decomposition<dim>::all_gather(const double v) const
{
  if (size == 1)
    return {v};
  return Utilities::MPI::all_gather(comm, v);
}

template <int dim>
std::string Decomposition<dim>::broadcast(const std::string &text,
                                          const unsigned int root) const
{
  if (size == 1)
    return text;
  return Utilities::MPI::broadcast(comm, text, root);
}

template class Decomposition<2>;
template class Decomposition<3>;
} // namespace lme_mpm
