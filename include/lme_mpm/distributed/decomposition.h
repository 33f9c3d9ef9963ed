#ifndef LME_MPM_DISTRIBUTED_DECOMPOSITION_H
#define LME_MPM_DISTRIBUTED_DECOMPOSITION_H

#include <deal.II/base/mpi.h>

#include <lme_mpm/base/rank_reductions.h>
#include <lme_mpm/distributed/halo.h>
#include <lme_mpm/grid/background_grid.h>
#include <lme_mpm/particles/particle_store.h>

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace lme_mpm
{
/**
 * The split of a run over MPI ranks. p4est (deal.II's
 * parallel::distributed::Triangulation over the background grid's cells) decides
 * which rank owns which cell; a rank owns the particles in its cells and keeps
 * copies (ghosts) of the other ranks' particles within a halo around them.
 *
 * The halo is as wide as everything one step of an owned particle depends on (its
 * support, the supports of the particles that share its nodes, the fracture
 * neighbourhood and crack band, the mass corrections' and contact's node-particle
 * passes), so every rank runs the serial step on its owned particles and ghosts
 * unchanged, and the owned particles come out of it as they would on one rank. The
 * ghosts' own results near the halo's outer edge are wrong (their nodes miss
 * particles) and are thrown away: after each step the owned particles that left
 * their rank's cells move to their new owner, and the ghosts are sent afresh. One
 * exchange of particles per step, no exchange of nodal values: the halo's extra work
 * buys the fewest messages.
 *
 * Particles are sorted by cell and by id within a cell (ParticleStore::sort_by_cell),
 * so a node sums the contributions of the same particles in the same order on any
 * number of ranks: the owned particles' states agree bit for bit with a one-rank
 * run (the test tests/mpi checks it).
 */
template <int dim>
class Decomposition : public RankReductions
{
public:
  explicit Decomposition(MPI_Comm comm = MPI_COMM_WORLD);

  unsigned int n_ranks() const { return size; }
  unsigned int rank() const { return my_rank; }
  bool distributed() const { return size > 1; }
  MPI_Comm communicator() const { return comm; }

  /**
   * Partitions the cells of @p grid with p4est and sets up the halo @p reach asks
   * for around this rank's cells: support passes first, then the direct particle
   * reach, then the margin. One rank: everything is owned.
   */
  void partition(const BackgroundGrid<dim> &grid, const HaloReach &reach);

  /// Owner rank of cell @p c (lexicographic index).
  unsigned int owner(const unsigned int c) const { return size > 1 ? cell_owner[c] : 0; }
  /**
   * True if this rank reports node @p n: the owner of the cell whose lowest corner it
   * is (the last cell for nodes on the upper grid faces). That rank holds every
   * particle near the node, so the node's values are complete there.
   */
  bool owns_node(const unsigned int n) const override
  {
    return node_owned.empty() || node_owned[n] != 0;
  }
  /// Per grid node: 1 where owns_node() (empty on one rank: every node).
  const std::vector<std::uint8_t> &owned_nodes() const { return node_owned; }
  /// Cells this rank owns, and cells in its halo.
  std::size_t n_owned_cells() const { return owned_cell_count; }
  std::size_t n_halo_cells() const { return halo_cell_count; }

  /**
   * From a store holding every particle (all ranks generated the same ones), keeps
   * this rank's: those in its cells, and ghosts of those in its halo.
   */
  void distribute(ParticleStore<dim> &particles) const;

  /**
   * After a step: drops the ghosts, sends the owned particles that moved to another
   * rank's cells to it, and sends every rank the owned particles in its halo.
   * Particles outside the grid stay where they are (the next step reports them).
   */
  void exchange(ParticleStore<dim> &particles);

  /**
   * Every rank's owned particles, on rank 0, in the order one rank holds them (by the
   * cell of the last sort, then id; empty on the others): what the output of a
   * distributed run reads.
   */
  void gather(const ParticleStore<dim> &particles, ParticleStore<dim> &all) const;

  /**
   * What a growing crack reads, the same on every rank: every rank's failed owned
   * particles and the intact ones within @p reach of a failed one, in @p view,
   * sorted by cell and id (the order one rank holds them in).
   */
  void gather_failed(const ParticleStore<dim> &particles, double reach,
                     ParticleStore<dim> &view) const;

  /// Owned (non-ghost) particles on this rank.
  static std::size_t n_owned(const ParticleStore<dim> &particles);

  // Reductions over the ranks (no-ops on one rank).
  double sum(double v) const override;
  void sum(std::vector<double> &v) const override;
  double max(double v) const override;
  void max(std::vector<double> &v) const override;
  unsigned long long sum(unsigned long long v) const;
  /// The smallest value over the ranks (and the rank that has it).
  unsigned long long min(unsigned long long v) const;
  /// Waits for every rank.
  void barrier() const
  {
    if (size > 1)
      MPI_Barrier(comm);
  }
  /// Every rank's @p v, in rank order, on every rank.
  std::vector<double> all_gather(double v) const;
  /// @p text of rank @p root on every rank.
  std::string broadcast(const std::string &text, unsigned int root = 0) const;

private:
  MPI_Comm comm;
  unsigned int size = 1, my_rank = 0;
  const BackgroundGrid<dim> *grid = nullptr;
  /// The cells the halo reaches (set by partition()).
  std::unique_ptr<HaloCells<dim>> halo;
  std::vector<unsigned int> cell_owner;
  std::vector<std::uint8_t> node_owned;
  /// Per cell: 1 if in this rank's halo (not owned).
  std::vector<std::uint8_t> in_halo;
  /// Per owned cell: the ranks whose halo holds it, as [offsets[c], offsets[c+1]).
  std::vector<std::uint32_t> ghost_offsets;
  std::vector<std::uint32_t> ghost_ranks;
  /// Where exchange() last wrote each ghost it received in place (tried first).
  std::vector<std::size_t> ghost_slots;
  /// Messages to each rank, kept with their capacity between exchanges.
  std::vector<std::vector<char>> out;
  /// Message memory kept from one call to the next, as `out`: a message received
  /// into freshly allocated memory is copied several times slower, since its pages
  /// are mapped during the copy. The gather's are scratch of a const call.
  std::vector<char> send_buffer, arrived_buffer, ghost_buffer;
  mutable std::vector<char> gather_mine, gather_received;
  std::size_t owned_cell_count = 0, halo_cell_count = 0;
};
} // namespace lme_mpm

#endif
