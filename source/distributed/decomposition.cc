#include <deal.II/distributed/tria.h>
#include <deal.II/grid/grid_generator.h>

#include <lme_mpm/base/input.h>
#include <lme_mpm/distributed/decomposition.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace lme_mpm
{
namespace
{
/// Calls f(field, bytes of one element) for every field of the store, in order.
template <int dim, class F>
void for_fields(const ParticleStore<dim> &particles, F &&f)
{
  // for_each_field is the one list of fields; it only reads here.
  const_cast<ParticleStore<dim> &>(particles).for_each_field(
      [&](auto &field)
      {
        using T = typename std::decay_t<decltype(field)>::value_type;
        f(field, sizeof(T));
      });
}

/**
 * Boxes of cells on a grid of n[d] cells per direction: tells whether a box holds a
 * flagged cell (summed-area table) and flags the union of many boxes (a difference
 * array), each in O(1) per box, so halos of any width cost O(cells) per pass.
 */
template <int dim>
class CellBoxes
{
public:
  /// Cells [lo[d], hi[d]) along each direction d.
  struct Box
  {
    std::array<unsigned int, dim> lo, hi;
  };

  explicit CellBoxes(const std::array<unsigned int, dim> &n) : n(n)
  {
    std::size_t s = 1;
    for (unsigned int d = 0; d < dim; ++d)
      stride[d] = s, s *= n[d] + 1;
    values.resize(s);
  }

  /// Makes any() answer for the cells flagged in @p mask (lexicographic order).
  void tabulate(const std::vector<std::uint8_t> &mask)
  {
    std::fill(values.begin(), values.end(), 0);
    for_cells([&](const std::size_t c, const std::array<unsigned int, dim> &ijk)
              { values[corner(ijk, 1)] = mask[c]; });
    prefix_sums();
  }
  bool any(const Box &b) const
  {
    std::int64_t count = 0;
    for (unsigned int k = 0; k < (1u << dim); ++k)
    {
      std::size_t at = 0;
      int sign       = 1;
      for (unsigned int d = 0; d < dim; ++d)
        if (k & (1u << d))
          at += stride[d] * b.hi[d];
        else
          at += stride[d] * b.lo[d], sign = -sign;
      count += sign * values[at];
    }
    return count != 0;
  }

  /// Starts flagging boxes.
  void clear() { std::fill(values.begin(), values.end(), 0); }
  void paint(const Box &b)
  {
    for (unsigned int k = 0; k < (1u << dim); ++k)
    {
      std::size_t at = 0;
      int sign       = 1;
      for (unsigned int d = 0; d < dim; ++d)
        if (k & (1u << d))
          at += stride[d] * b.hi[d], sign = -sign;
        else
          at += stride[d] * b.lo[d];
      values[at] += sign;
    }
  }
  /// Flags in @p mask (ORed) every cell inside a painted box.
  void painted(std::vector<std::uint8_t> &mask)
  {
    prefix_sums();
    for_cells([&](const std::size_t c, const std::array<unsigned int, dim> &ijk)
              { mask[c] |= values[corner(ijk, 0)] > 0; });
  }

  template <class F>
  void for_cells(F &&f) const
  {
    std::array<unsigned int, dim> ijk{};
    std::size_t n_cells = 1;
    for (unsigned int d = 0; d < dim; ++d)
      n_cells *= n[d];
    for (std::size_t c = 0; c < n_cells; ++c)
    {
      f(c, ijk);
      for (unsigned int d = 0; d < dim && ++ijk[d] == n[d]; ++d)
        ijk[d] = 0;
    }
  }

private:
  std::size_t corner(const std::array<unsigned int, dim> &ijk,
                     const unsigned int shift) const
  {
    std::size_t at = 0;
    for (unsigned int d = 0; d < dim; ++d)
      at += stride[d] * (ijk[d] + shift);
    return at;
  }
  void prefix_sums()
  {
    for (unsigned int d = 0; d < dim; ++d)
      for (std::size_t f = 0; f < values.size(); ++f)
        if ((f / stride[d]) % (n[d] + 1) != 0)
          values[f] += values[f - stride[d]];
  }

  std::array<unsigned int, dim> n;
  std::array<std::size_t, dim> stride;
  std::vector<std::int64_t> values;
};

/// Cells of @p c (node coordinates) within @p r of [a, b], as [lo, hi).
inline void cells_near(const std::vector<double> &c, const double a, const double b,
                       const double r, unsigned int &lo, unsigned int &hi)
{
  // A cell [c[m], c[m+1]] is near if c[m+1] >= a - r and c[m] <= b + r; a hair of
  // slack keeps a boundary case in.
  const double slack = 1e-12 * (c.back() - c.front());
  const auto first   = std::lower_bound(c.begin(), c.end(), a - r - slack);
  const auto last    = std::upper_bound(c.begin(), c.end(), b + r + slack);
  const long n_cells = static_cast<long>(c.size()) - 1;
  lo = static_cast<unsigned int>(std::max<long>(0, (first - c.begin()) - 1));
  hi = static_cast<unsigned int>(std::min<long>(n_cells, last - c.begin()));
  lo = std::min(lo, hi);
}

/// Where each rank's piece starts in a message of pieces @p counts long; the total.
std::size_t displacements(const std::vector<int> &counts, std::vector<int> &at)
{
  std::size_t total = 0;
  for (std::size_t r = 0; r < counts.size(); ++r)
  {
    at[r] = static_cast<int>(total);
    total += counts[r];
  }
  return total;
}

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
std::size_t Decomposition<dim>::bytes_per_particle()
{
  ParticleStore<dim> probe;
  std::size_t bytes = 0;
  for_fields(probe, [&](const auto &, const std::size_t b) { bytes += b; });
  return bytes;
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
void Decomposition<dim>::partition(const BackgroundGrid<dim> &g, const Reach &reach)
{
  grid = &g;
  if (size == 1)
    return;
  const unsigned int n_cells = g.n_cells();
  AssertThrow(reach.node_radius.size() == g.n_nodes() &&
                  (reach.cell_radius.empty() || reach.cell_radius.size() == n_cells),
              ExcInternalError());

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
  const auto around_mine = reached(mine, reach);
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
      const auto around = reached(theirs, reach);
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
std::vector<std::uint8_t>
Decomposition<dim>::reached(const std::vector<std::uint8_t> &mask,
                            const Reach &reach) const
{
  using Box = typename CellBoxes<dim>::Box;
  std::array<unsigned int, dim> n;
  for (unsigned int d = 0; d < dim; ++d)
    n[d] = grid->n_cells_in(d);
  CellBoxes<dim> boxes(n);
  std::vector<std::uint8_t> out = mask;

  // A node's box: the cells within its radius (a box holds the ball).
  std::vector<Box> node_box;
  if (reach.support_passes > 0)
  {
    node_box.resize(grid->n_nodes());
    std::array<unsigned int, dim> ijk{};
    for (unsigned int a = 0; a < grid->n_nodes(); ++a)
    {
      for (unsigned int d = 0; d < dim; ++d)
      {
        const double x = grid->coordinates(d)[ijk[d]];
        cells_near(grid->coordinates(d), x, x, reach.node_radius[a], node_box[a].lo[d],
                   node_box[a].hi[d]);
      }
      for (unsigned int d = 0; d < dim && ++ijk[d] == grid->n_nodes_in(d); ++d)
        ijk[d] = 0;
    }
  }
  for (unsigned int pass = 0; pass < reach.support_passes; ++pass)
  {
    // The nodes coupled to a flagged cell's particles, then their particles' cells.
    boxes.tabulate(out);
    std::vector<std::uint8_t> touched(node_box.size());
    for (std::size_t a = 0; a < node_box.size(); ++a)
      touched[a] = boxes.any(node_box[a]);
    boxes.clear();
    for (std::size_t a = 0; a < node_box.size(); ++a)
      if (touched[a])
        boxes.paint(node_box[a]);
    boxes.painted(out);
  }

  if (!reach.cell_radius.empty())
  {
    std::vector<Box> cell_box(out.size());
    boxes.for_cells(
        [&](const std::size_t c, const std::array<unsigned int, dim> &ijk)
        {
          for (unsigned int d = 0; d < dim; ++d)
            cells_near(grid->coordinates(d), grid->coordinates(d)[ijk[d]],
                       grid->coordinates(d)[ijk[d] + 1], reach.cell_radius[c],
                       cell_box[c].lo[d], cell_box[c].hi[d]);
        });
    // A cell reaching a flagged one, and every cell a flagged one reaches.
    boxes.tabulate(out);
    std::vector<std::uint8_t> next = out;
    for (std::size_t c = 0; c < out.size(); ++c)
      next[c] |= boxes.any(cell_box[c]);
    boxes.clear();
    for (std::size_t c = 0; c < out.size(); ++c)
      if (out[c])
        boxes.paint(cell_box[c]);
    boxes.painted(next);
    out.swap(next);
  }

  if (reach.margin_cells > 0)
  {
    std::array<unsigned int, dim> k;
    k.fill(reach.margin_cells);
    out = dilate(out, k);
  }
  return out;
}

template <int dim>
std::array<unsigned int, dim> Decomposition<dim>::cells_within(const double width) const
{
  // The width over the narrowest cells of each direction, and one cell more (a
  // particle sits anywhere in its cell).
  std::array<unsigned int, dim> k;
  for (unsigned int d = 0; d < dim; ++d)
  {
    double h = std::numeric_limits<double>::max();
    for (unsigned int i = 0; i < grid->n_cells_in(d); ++i)
      h = std::min(h, grid->spacing(d, i));
    k[d] = static_cast<unsigned int>(
        std::min<double>(grid->n_cells_in(d), std::ceil(width / h - 1e-9) + 1));
  }
  return k;
}

template <int dim>
std::vector<std::uint8_t>
Decomposition<dim>::dilate(const std::vector<std::uint8_t> &mask,
                           const std::array<unsigned int, dim> &reach) const
{
  std::array<unsigned int, dim> n;
  for (unsigned int d = 0; d < dim; ++d)
    n[d] = grid->n_cells_in(d);
  CellBoxes<dim> boxes(n);
  boxes.for_cells(
      [&](const std::size_t c, const std::array<unsigned int, dim> &ijk)
      {
        if (!mask[c])
          return;
        typename CellBoxes<dim>::Box b;
        for (unsigned int d = 0; d < dim; ++d)
          b.lo[d] = ijk[d] > reach[d] ? ijk[d] - reach[d] : 0,
          b.hi[d] = std::min(n[d], ijk[d] + reach[d] + 1);
        boxes.paint(b);
      });
  std::vector<std::uint8_t> out = mask;
  boxes.painted(out);
  return out;
}

template <int dim>
void Decomposition<dim>::pack(const ParticleStore<dim> &particles, const std::size_t p,
                              std::vector<char> &buffer)
{
  // One resize per particle: the per-field ones cost more than the copies.
  static const std::size_t total = bytes_per_particle();
  char *at                       = nullptr;
  {
    const std::size_t end = buffer.size();
    buffer.resize(end + total);
    at = buffer.data() + end;
  }
  for_fields(particles,
             [&](const auto &field, const std::size_t bytes)
             {
               std::memcpy(at, &field[p], bytes);
               at += bytes;
             });
}

template <int dim>
void Decomposition<dim>::unpack(const std::vector<char> &buffer,
                                ParticleStore<dim> &particles, const std::uint8_t ghost)
{
  const std::size_t bytes = bytes_per_particle();
  AssertThrow(buffer.size() % bytes == 0, ExcInternalError());
  const std::size_t n = buffer.size() / bytes, first = particles.size();
  particles.resize(first + n);
  std::size_t at = 0;
  for (std::size_t k = 0; k < n; ++k)
    particles.for_each_field(
        [&](auto &field)
        {
          using T = typename std::decay_t<decltype(field)>::value_type;
          std::memcpy(&field[first + k], buffer.data() + at, sizeof(T));
          at += sizeof(T);
        });
  for (std::size_t p = first; p < first + n; ++p)
    particles.ghost[p] = ghost;
}

template <int dim>
void Decomposition<dim>::compact(ParticleStore<dim> &particles,
                                 const std::vector<std::uint8_t> &keep)
{
  const std::size_t n = particles.size();
  std::size_t kept    = 0;
  particles.for_each_field(
      [&](auto &field)
      {
        kept = 0;
        for (std::size_t p = 0; p < n; ++p)
          if (keep[p])
            field[kept++] = field[p];
      });
  particles.resize(kept);
}

template <int dim>
std::vector<char>
Decomposition<dim>::all_to_all(const std::vector<std::vector<char>> &out) const
{
  std::vector<int> send_counts(size), recv_counts(size), send_at(size), recv_at(size);
  std::vector<char> send;
  for (unsigned int r = 0; r < size; ++r)
  {
    AssertThrow(out[r].size() < std::size_t(std::numeric_limits<int>::max()) / 2,
                ExcMessage("a particle message over 1 GB: use more ranks"));
    send_counts[r] = static_cast<int>(out[r].size());
    send_at[r]     = static_cast<int>(send.size());
    send.insert(send.end(), out[r].begin(), out[r].end());
  }
  MPI_Alltoall(send_counts.data(), 1, MPI_INT, recv_counts.data(), 1, MPI_INT, comm);
  const std::size_t total = displacements(recv_counts, recv_at);
  AssertThrow(total < std::size_t(std::numeric_limits<int>::max()),
              ExcMessage("a rank receives over 2 GB of particles in one step: use more "
                         "ranks"));
  std::vector<char> received(total);
  MPI_Alltoallv(send.data(), send_counts.data(), send_at.data(), MPI_CHAR,
                received.data(), recv_counts.data(), recv_at.data(), MPI_CHAR, comm);
  return received;
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
  compact(particles, keep);
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
  std::vector<std::uint8_t> keep(n, 0);
  // The cells of the particles kept, in their order after compact(): each particle
  // is located once.
  std::vector<unsigned int> cells;
  std::vector<std::vector<char>> out(size);
  for (std::size_t p = 0; p < n; ++p)
  {
    if (particles.ghost[p])
      continue;
    const unsigned int c = cell_of(p);
    // Off the grid: kept, and the next step stops the run and names it.
    if (c == off_grid || cell_owner[c] == my_rank)
      keep[p] = 1, cells.push_back(c);
    else
      pack(particles, p, out[cell_owner[c]]);
  }
  compact(particles, keep);
  unpack(all_to_all(out), particles, 0);
  for (std::size_t p = cells.size(); p < particles.size(); ++p)
    cells.push_back(cell_of(p));

  // Ghosts afresh: every owned particle to the ranks whose halo holds its cell.
  for (auto &o : out)
    o.clear();
  for (std::size_t p = 0; p < particles.size(); ++p)
    if (cells[p] != off_grid)
      for (std::uint32_t k = ghost_offsets[cells[p]]; k < ghost_offsets[cells[p] + 1];
           ++k)
        pack(particles, p, out[ghost_ranks[k]]);
  unpack(all_to_all(out), particles, 1);
  particles.mark_reordered();
}

template <int dim>
void Decomposition<dim>::gather(const ParticleStore<dim> &particles,
                                ParticleStore<dim> &all) const
{
  all.resize(0);
  std::vector<char> mine;
  for (std::size_t p = 0; p < particles.size(); ++p)
    if (!particles.ghost[p])
      pack(particles, p, mine);
  int count = static_cast<int>(mine.size());
  std::vector<int> counts(size), at(size);
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
  const std::size_t total = displacements(counts, at);
  AssertThrow(total < std::size_t(std::numeric_limits<int>::max()),
              ExcMessage("the particles gathered for output exceed 2 GB: write less "
                         "often, or run fewer particles per job"));
  std::vector<char> received(my_rank == 0 ? total : 0);
  MPI_Gatherv(mine.data(), count, MPI_CHAR, received.data(), counts.data(), at.data(),
              MPI_CHAR, 0, comm);
  if (my_rank != 0)
    return;
  unpack(received, all, 0);
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
    cells = dilate(cells, cells_within(reach));
    for (std::size_t p = 0; p < particles.size(); ++p)
      if (!particles.ghost[p] && grid->locate(particles.position[p], ijk) &&
          cells[grid->cell_index(ijk)])
        pack(particles, p, mine);
  }
  if (size == 1)
  {
    unpack(mine, view, 0);
  }
  else
  {
    const std::vector<std::vector<char>> everyone =
        Utilities::MPI::all_gather(comm, mine);
    for (const auto &piece : everyone)
      unpack(piece, view, 0);
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
