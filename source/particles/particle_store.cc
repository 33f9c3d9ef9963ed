#include <lme_mpm/particles/particle_store.h>

#include <algorithm>

namespace lme_mpm
{
template <int dim>
void ParticleStore<dim>::resize(const std::size_t n)
{
  const std::size_t old = strength.size();
  for_each_field([n](auto &v) { v.resize(n); });
  // A new particle has its material's strength until a strength field says otherwise.
  if (optional.fracture && n > old)
    std::fill(strength.begin() + old, strength.end(), 1.0);
  ++version;
}

template <int dim>
void ParticleStore<dim>::keep_state(const OptionalState &kept)
{
  optional = kept;
  visit_fields(
      [](auto &field, const bool keep)
      {
        if (!keep)
          std::decay_t<decltype(field)>().swap(field);
      },
      true);
  resize(size());
}

template <int dim>
std::size_t ParticleStore<dim>::bytes_per_particle() const
{
  std::size_t bytes = 0;
  const_cast<ParticleStore<dim> *>(this)->for_each_field(
      [&](auto &field)
      { bytes += sizeof(typename std::decay_t<decltype(field)>::value_type); });
  return bytes;
}

template <int dim>
std::size_t ParticleStore<dim>::add(const Point<dim> &x, const double m, const double v,
                                    const unsigned int material, const unsigned int body)
{
  const std::size_t p = size();
  resize(p + 1);
  position[p]           = x;
  reference_position[p] = x;
  mass[p]               = m;
  volume[p]             = v;
  initial_volume[p]     = v;
  density[p]            = m / v;
  id[p]                 = static_cast<std::uint32_t>(p);
  material_id[p]        = static_cast<std::uint16_t>(material);
  body_id[p]            = static_cast<std::uint16_t>(body);
  return p;
}

template <int dim>
bool ParticleStore<dim>::sort_by_cell(const unsigned int n_cells)
{
  const std::size_t n = size();
  offsets.assign(n_cells + 1, 0);
  bool sorted = true;
  for (std::size_t p = 0; p < n; ++p)
  {
    ++offsets[cell[p] + 1];
    if (p > 0 && (cell[p] < cell[p - 1] || (cell[p] == cell[p - 1] && id[p] < id[p - 1])))
      sorted = false;
  }
  for (unsigned int c = 0; c < n_cells; ++c)
    offsets[c + 1] += offsets[c];
  if (sorted)
    return false;

  permutation.resize(n);
  std::vector<std::size_t> next(offsets.begin(), offsets.end() - 1);
  for (std::size_t p = 0; p < n; ++p)
    permutation[next[cell[p]]++] = static_cast<std::uint32_t>(p);
  // Within a cell by id, stably: insertion sort for the few particles of a cell, a
  // merge sort where many share one (the cells are not located yet, as in output
  // gathered before the first step).
  for (unsigned int c = 0; c < n_cells; ++c)
  {
    if (offsets[c + 1] - offsets[c] > 32)
    {
      std::stable_sort(
          permutation.begin() + offsets[c], permutation.begin() + offsets[c + 1],
          [this](const std::uint32_t a, const std::uint32_t b) { return id[a] < id[b]; });
      continue;
    }
    for (std::size_t q = offsets[c] + 1; q < offsets[c + 1]; ++q)
    {
      const std::uint32_t moving = permutation[q];
      std::size_t r              = q;
      for (; r > offsets[c] && id[permutation[r - 1]] > id[moving]; --r)
        permutation[r] = permutation[r - 1];
      permutation[r] = moving;
    }
  }

  // Moved in place along the permutation's cycles, each field walked from the same
  // starts: a particle that keeps its place costs one look, and no field is copied
  // whole (a copy of the largest field was part of a run's peak memory).
  std::vector<std::uint32_t> starts;
  {
    std::vector<bool> seen(n, false);
    for (std::size_t q = 0; q < n; ++q)
    {
      if (seen[q] || permutation[q] == q)
        continue;
      starts.push_back(static_cast<std::uint32_t>(q));
      for (std::size_t k = q; !seen[k]; k = permutation[k])
        seen[k] = true;
    }
  }
  for_each_field(
      [this, &starts](auto &field)
      {
        for (const std::uint32_t q : starts)
        {
          // The particle now at k was at permutation[k]: fill the cycle from q on.
          const auto first = field[q];
          std::size_t k    = q;
          for (std::size_t from = permutation[k]; from != q; from = permutation[k])
          {
            field[k] = field[from];
            k        = from;
          }
          field[k] = first;
        }
      });
  sorted_at = ++version;
  return true;
}

template class ParticleStore<2>;
template class ParticleStore<3>;
} // namespace lme_mpm
