#include "particle_messages.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <type_traits>
#include <utility>

namespace lme_mpm
{
namespace particle_messages
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

/// Copies the n particles packed in @p buffer into the store's slots target(k).
template <int dim, class Target>
void copy_in(const std::vector<char> &buffer, const std::size_t n,
             ParticleStore<dim> &particles, const Target &target)
{
  std::size_t at = 0;
  for (std::size_t k = 0; k < n; ++k)
  {
    const std::size_t slot = target(k);
    particles.for_each_field(
        [&](auto &field)
        {
          using T = typename std::decay_t<decltype(field)>::value_type;
          std::memcpy(&field[slot], buffer.data() + at, sizeof(T));
          at += sizeof(T);
        });
  }
}
} // namespace

template <int dim>
void pack(const ParticleStore<dim> &particles, const std::size_t p,
          std::vector<char> &buffer)
{
  // One resize per particle: the per-field ones cost more than the copies.
  const std::size_t total = particles.bytes_per_particle();
  char *at                = nullptr;
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
void unpack(const std::vector<char> &buffer, ParticleStore<dim> &particles,
            const std::uint8_t ghost)
{
  // The sender kept the same fields (every rank's store keeps the run's state).
  const std::size_t bytes = particles.bytes_per_particle();
  AssertThrow(buffer.size() % bytes == 0, ExcInternalError());
  const std::size_t n = buffer.size() / bytes, first = particles.size();
  particles.resize(first + n);
  copy_in(buffer, n, particles, [first](const std::size_t k) { return first + k; });
  for (std::size_t p = first; p < first + n; ++p)
    particles.ghost[p] = ghost;
}

template <int dim>
bool refill_ghosts(const std::vector<char> &buffer, ParticleStore<dim> &particles,
                   std::vector<std::size_t> &slots)
{
  const std::size_t bytes = particles.bytes_per_particle();
  AssertThrow(buffer.size() % bytes == 0, ExcInternalError());
  const std::size_t n = buffer.size() / bytes;
  std::size_t n_held  = 0;
  for (const std::uint8_t g : particles.ghost)
    n_held += g;
  if (n_held != n)
    return false;
  // Where the id lies in a packed particle.
  std::size_t id_at = 0;
  {
    bool found = false;
    for_fields(particles,
               [&](const auto &field, const std::size_t field_bytes)
               {
                 if constexpr (std::is_same_v<std::decay_t<decltype(field)>,
                                              std::vector<std::uint32_t>>)
                   found = found || &field == &particles.id;
                 if (!found)
                   id_at += field_bytes;
               });
    AssertThrow(found, ExcInternalError());
  }
  const auto id_of = [&](const std::size_t k)
  {
    std::uint32_t id;
    std::memcpy(&id, buffer.data() + k * bytes + id_at, sizeof(id));
    return id;
  };
  // A particle is sent once to each rank, so the ids that arrive are distinct, and
  // as many as the ghosts held: if each is a ghost's id, each has one slot. The
  // slots of the last refill hold unless a sender or this store was reordered.
  bool same = slots.size() == n;
  for (std::size_t k = 0; same && k < n; ++k)
    same = slots[k] < particles.size() && particles.ghost[slots[k]] &&
           particles.id[slots[k]] == id_of(k);
  if (!same)
  {
    std::vector<std::pair<std::uint32_t, std::size_t>> held;
    held.reserve(n);
    for (std::size_t p = 0; p < particles.size(); ++p)
      if (particles.ghost[p])
        held.emplace_back(particles.id[p], p);
    std::sort(held.begin(), held.end());
    std::vector<std::size_t> found(n);
    for (std::size_t k = 0; k < n; ++k)
    {
      const std::uint32_t id = id_of(k);
      const auto it =
          std::lower_bound(held.begin(), held.end(), std::make_pair(id, std::size_t(0)));
      if (it == held.end() || it->first != id)
        return false;
      found[k] = it->second;
    }
    slots.swap(found);
  }
  copy_in(buffer, n, particles, [&slots](const std::size_t k) { return slots[k]; });
  // The sender's flag (owned there) came with the rest.
  for (const std::size_t p : slots)
    particles.ghost[p] = 1;
  return true;
}

template <int dim>
void compact(ParticleStore<dim> &particles, const std::vector<std::uint8_t> &keep)
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

void all_to_all(MPI_Comm comm, const std::vector<std::vector<char>> &out,
                std::vector<char> &send, std::vector<char> &received)
{
  const std::size_t size = out.size();
  std::vector<int> send_counts(size), recv_counts(size), send_at(size), recv_at(size);
  send.clear();
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
  received.resize(total);
  MPI_Alltoallv(send.data(), send_counts.data(), send_at.data(), MPI_CHAR,
                received.data(), recv_counts.data(), recv_at.data(), MPI_CHAR, comm);
}

template void pack(const ParticleStore<2> &, std::size_t, std::vector<char> &);
template void pack(const ParticleStore<3> &, std::size_t, std::vector<char> &);
template void unpack(const std::vector<char> &, ParticleStore<2> &, std::uint8_t);
template void unpack(const std::vector<char> &, ParticleStore<3> &, std::uint8_t);
template bool refill_ghosts(const std::vector<char> &, ParticleStore<2> &,
                            std::vector<std::size_t> &);
template bool refill_ghosts(const std::vector<char> &, ParticleStore<3> &,
                            std::vector<std::size_t> &);
template void compact(ParticleStore<2> &, const std::vector<std::uint8_t> &);
template void compact(ParticleStore<3> &, const std::vector<std::uint8_t> &);
} // namespace particle_messages
} // namespace lme_mpm
