// Simulation: checkpoints, resuming from them, and the state checksum. Checkpointing
// touches every part, so it stays with the owner of the parts.
#include <lme_mpm/base/checkpoint.h>
#include <lme_mpm/base/format.h>
#include <lme_mpm/base/input.h>
#include <lme_mpm/simulation/simulation.h>

#include <filesystem>
#include <sstream>

namespace lme_mpm
{
template <int dim>
void Simulation<dim>::serialize(Archive &ar)
{
  // Everything a resumed run needs to continue bit for bit: the particles, the
  // accumulators of the step and the output, and the output series. Nodal fields
  // are rebuilt every step. A distributed run writes one file per rank, each with
  // that rank's particles (owned and ghosts) and its copy of the rest: it resumes on
  // as many ranks, which p4est splits alike.
  std::uint32_t file_dim = dim, file_steps = clock.planned_steps(),
                file_ranks = parts.ranks.n_ranks();
  std::uint64_t n          = n_particles;
  double file_dt           = clock.wave_step();
  ar(file_dim, file_ranks, n, file_dt, file_steps);
  if (ar.loading())
  {
    std::ostringstream mismatch;
    mismatch << "the checkpoint holds a " << file_dim << "D run of " << n
             << " particles with dt = " << file_dt << " s; this parameter file gives "
             << dim << "D, " << n_particles << " particles, dt = " << clock.wave_step()
             << " s: resume with the parameter file (and --set "
             << "values) of the run that wrote it";
    AssertThrow(file_dim == dim && n == n_particles && file_dt == clock.wave_step(),
                ExcBadInput("--resume", mismatch.str()));
    AssertThrow(file_ranks == parts.ranks.n_ranks(),
                ExcBadInput("--resume", "the checkpoint was written on " +
                                            std::to_string(file_ranks) +
                                            " MPI ranks; resume on as many (mpirun -np " +
                                            std::to_string(file_ranks) + ")"));
  }
  ar(t, step_count);
  parts.transfer.serialize(ar);
  ar(max_speed);
  clock.serialize(ar);
  output.serialize(ar);
  parts.constraints.serialize(ar);
  parts.contact.serialize(ar);
  parts.rigid.serialize(ar);
  parts.control.serialize(ar);
  parts.scene->serialize(ar);
  parts.particles.for_each_field([&](auto &field) { ar(field); });
  auto lines = parts.cracks.polylines();
  ar(lines);
  // A changed entry that the checks above let through is named here.
  output.serialize_parameters(ar);
  if (!ar.loading())
    return;
  AssertThrow(
      ar.good() && lines.size() == parts.cracks.polylines().size(),
      ExcBadInput("--resume", "the checkpoint holds " + std::to_string(lines.size()) +
                                  " cracks, the parameter file " +
                                  std::to_string(parts.cracks.polylines().size())));
  parts.cracks.restore(std::move(lines));
  parts.transfer.nodes().layout.reinit(parts.grid.n_nodes());
  parts.cracks.assign_fields(parts.grid, crack_reach, parts.transfer.nodes().layout);
}

template <int dim>
bool Simulation<dim>::checkpoint_due(
    const std::chrono::steady_clock::time_point last) const
{
  const RunParameters<dim> &run = parts.parameters;
  const bool by_steps =
      run.checkpoint_every_steps > 0 && step_count % run.checkpoint_every_steps == 0;
  // Every rank writes its part at the same step: the slowest rank's clock decides.
  const bool by_time = run.checkpoint_every_seconds > 0 &&
                       parts.ranks.max(std::chrono::duration<double>(
                                           std::chrono::steady_clock::now() - last)
                                           .count()) >= run.checkpoint_every_seconds;
  return by_steps || by_time;
}

template <int dim>
void Simulation<dim>::write_checkpoint()
{
  checkpoint::write(checkpoint_file(output.directory()),
                    [&](Archive &ar) { serialize(ar); });
}

template <int dim>
std::string Simulation<dim>::checkpoint_file(const std::string &directory) const
{
  return directory + (parts.ranks.distributed()
                          ? "/checkpoint." + std::to_string(parts.ranks.rank()) + ".bin"
                          : "/checkpoint.bin");
}

template <int dim>
void Simulation<dim>::resume_from(const std::string &directory)
{
  // Output goes on in the checkpoint's directory.
  output.open(directory);
  // Files of a run on another number of ranks: name the number to use. Every rank
  // decides alike from the same files (one rank stopping alone would leave the
  // others waiting).
  const Decomposition<dim> &ranks = parts.ranks;
  const std::string file          = checkpoint_file(directory);
  unsigned int per_rank           = 0;
  while (std::filesystem::exists(directory + "/checkpoint." + std::to_string(per_rank) +
                                 ".bin"))
    ++per_rank;
  const bool one_rank           = std::filesystem::exists(directory + "/checkpoint.bin");
  const unsigned int written_on = ranks.distributed() ? (per_rank > 0 ? per_rank
                                                         : one_rank   ? 1
                                                                      : 0)
                                                      : (one_rank ? 1 : per_rank);
  AssertThrow(written_on == 0 || written_on == ranks.n_ranks(),
              ExcBadInput("--resume", "the checkpoint in '" + directory +
                                          "' was written on " +
                                          std::to_string(written_on) +
                                          " MPI rank(s): resume on as many (mpirun -np " +
                                          std::to_string(written_on) + ")"));
  if (ranks.distributed())
    AssertThrow(ranks.min(std::filesystem::exists(file) ? 1ull : 0ull) == 1,
                ExcBadInput("--resume", "no checkpoint '" + file + "' on every rank"));
  checkpoint::read(file, [&](Archive &ar) { serialize(ar); });
  if (ranks.distributed())
  {
    // A checkpoint that some rank could not complete (a full disk) leaves the ranks'
    // latest files at different steps: those ahead go back to their previous one.
    const unsigned long long lowest =
        ranks.min(static_cast<unsigned long long>(step_count));
    if (step_count != lowest && std::filesystem::exists(file + ".prev"))
      checkpoint::read(file + ".prev", [&](Archive &ar) { serialize(ar); });
    AssertThrow(
        ranks.min(step_count == lowest ? 1ull : 0ull) == 1,
        ExcBadInput("--resume", "the ranks' checkpoints in '" + directory +
                                    "' are of different steps, and no step is " +
                                    "held by every rank's latest or previous one"));
  }
  parts.particles.mark_reordered();
  AssertThrow(t < clock.end_time(),
              ExcBadInput("--resume", "the checkpoint (t = " + format_double(t) +
                                          " s) is past this run's Time/End time = " +
                                          format_double(clock.end_time()) + " s"));
  resumed = true;
  stepper.mark_initialised();
}

template <int dim>
std::uint64_t Simulation<dim>::state_checksum()
{
  // FNV-1a of each owned particle's fields, summed over the particles (and ranks):
  // the same state gives the same sum whatever the order and split of the particles.
  auto fnv = [](std::uint64_t hash, const void *data, const std::size_t size)
  {
    const auto *c = static_cast<const unsigned char *>(data);
    for (std::size_t i = 0; i < size; ++i)
      hash = (hash ^ c[i]) * 1099511628211ull;
    return hash;
  };
  constexpr std::uint64_t basis = 1469598103934665603ull;
  unsigned long long total      = 0;
  ParticleStore<dim> &store     = parts.particles;
  for (std::size_t p = 0; p < store.size(); ++p)
    if (!store.ghost[p])
    {
      std::uint64_t hash = basis;
      // A dropped field counts as the value it stands for, so the checksum does not
      // depend on which state a run keeps.
      store.for_all_fields(
          [&](auto &field)
          {
            const auto value = store.value_at(field, p);
            hash             = fnv(hash, &value, sizeof(value));
          });
      total += hash;
    }
  return fnv(basis, &t, sizeof(t)) + parts.ranks.sum(total);
}

// The members defined in this file, for both dimensions (simulation.cc instantiates
// the rest).
#define LME_MPM_INSTANTIATE(D)                                                           \
  template void Simulation<D>::serialize(Archive &);                                     \
  template bool Simulation<D>::checkpoint_due(std::chrono::steady_clock::time_point)     \
      const;                                                                             \
  template void Simulation<D>::write_checkpoint();                                       \
  template std::string Simulation<D>::checkpoint_file(const std::string &) const;        \
  template void Simulation<D>::resume_from(const std::string &);                         \
  template std::uint64_t Simulation<D>::state_checksum();
LME_MPM_INSTANTIATE(2)
LME_MPM_INSTANTIATE(3)
#undef LME_MPM_INSTANTIATE
} // namespace lme_mpm
