#ifndef LME_MPM_DISTRIBUTED_PARTICLE_MESSAGES_H
#define LME_MPM_DISTRIBUTED_PARTICLE_MESSAGES_H

// Private to the library (not installed): particles packed into MPI messages.

#include <deal.II/base/mpi.h>

#include <lme_mpm/particles/particle_store.h>

#include <cstdint>
#include <vector>

namespace lme_mpm
{
/**
 * Particles as bytes: every field of the store (ParticleStore::for_each_field, the one
 * list of fields) copied in order, so a particle arrives as it left.
 */
namespace particle_messages
{
/// Appends particle @p p of @p particles to @p buffer.
template <int dim>
void pack(const ParticleStore<dim> &particles, std::size_t p, std::vector<char> &buffer);
/// Appends the particles in @p buffer to @p particles with their ghost flag @p ghost.
template <int dim>
void unpack(const std::vector<char> &buffer, ParticleStore<dim> &particles,
            std::uint8_t ghost);
/**
 * Writes the particles in @p buffer over the ghosts of @p particles with the same ids,
 * if the ghosts are exactly those particles (as many, each id among them); returns
 * false and changes no particle otherwise. @p slots: where the last refill wrote each
 * particle of its buffer, tried first (a buffer in the same order, a store not
 * reordered since); on return true, where this one wrote them.
 */
template <int dim>
bool refill_ghosts(const std::vector<char> &buffer, ParticleStore<dim> &particles,
                   std::vector<std::size_t> &slots);
/// Keeps the particles with keep[p] != 0, in order.
template <int dim>
void compact(ParticleStore<dim> &particles, const std::vector<std::uint8_t> &keep);

/// Where each rank's piece starts in a message of pieces @p counts long; the total.
std::size_t displacements(const std::vector<int> &counts, std::vector<int> &at);
/**
 * Sends @p out[r] to rank r of @p comm; @p received: what the ranks sent here, in
 * rank order. @p send and @p received are the caller's, so that they keep their
 * capacity from one call to the next: a message received into freshly allocated
 * memory is copied several times slower (its pages are mapped during the copy).
 */
void all_to_all(MPI_Comm comm, const std::vector<std::vector<char>> &out,
                std::vector<char> &send, std::vector<char> &received);
} // namespace particle_messages
} // namespace lme_mpm

#endif
