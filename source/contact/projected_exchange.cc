#include <lme_mpm/base/parallel.h>
#include <lme_mpm/contact/projected_exchange.h>

#include <algorithm>

namespace lme_mpm
{
template <int dim>
void ProjectedExchange<dim>::respond(const std::vector<ExchangePair<dim>> &pairs,
                                     GridTransfer<dim> &transfer,
                                     const ParticleStore<dim> &particles,
                                     const std::vector<std::uint8_t> &touches,
                                     const std::vector<Tensor<1, dim>> &impulse_on_a)
{
  const NodalFields<dim> &nodes = transfer.nodes();
  const Connectivity<dim> &conn = transfer.connectivity();
  for (const auto &q : pairs)
    jump[q.a] = jump[q.b] = Tensor<1, dim>();
  for (std::size_t i = 0; i < pairs.size(); ++i)
  {
    const auto &q = pairs[i];
    if (!q.fixed_a)
      jump[q.a] += impulse_on_a[i] / nodes.mass[q.a];
    if (!q.fixed_b)
      jump[q.b] -= impulse_on_a[i] / nodes.mass[q.b];
  }
  parallel::for_range(touching.size(),
                      [&](const std::size_t b, const std::size_t e)
                      {
                        for (std::size_t i = b; i < e; ++i)
                        {
                          const std::size_t p = touching[i];
                          const std::size_t o = p * conn.stride;
                          Tensor<1, dim> d;
                          for (unsigned int k = 0; k < conn.n_nodes[p]; ++k)
                            if (in_pair[conn.nodes[o + k]])
                              d += conn.N[o + k] * jump[conn.nodes[o + k]];
                          delta[p] = d;
                        }
                      });
  // Every field the jumping particles reach, zeroed before the scatter.
  for (const std::size_t p : touching)
  {
    const std::size_t o = p * conn.stride;
    for (unsigned int k = 0; k < conn.n_nodes[p]; ++k)
      response[conn.nodes[o + k]] = Tensor<1, dim>();
  }
  transfer.scatter(
      [&](const std::size_t p)
      {
        if (!touches[p])
          return;
        const std::size_t o      = p * conn.stride;
        const Tensor<1, dim> mdv = particles.mass[p] * delta[p];
        for (unsigned int k = 0; k < conn.n_nodes[p]; ++k)
          response[conn.nodes[o + k]] += conn.N[o + k] * mdv;
      });
}

template <int dim>
bool ProjectedExchange<dim>::warm_start(const std::vector<ExchangePair<dim>> &pairs,
                                        std::vector<Tensor<1, dim>> &impulse_on_a) const
{
  // A pair in contact in the last step starts from the impulse it had then
  // (quasi-static loading changes it little from step to step).
  bool warm = false;
  for (std::size_t i = 0; i < pairs.size(); ++i)
  {
    const auto it = std::lower_bound(last_keys.begin(), last_keys.end(), pairs[i].key);
    if (it != last_keys.end() && *it == pairs[i].key)
    {
      impulse_on_a[i] = last_impulses[it - last_keys.begin()];
      warm            = true;
    }
  }
  return warm;
}

template <int dim>
void ProjectedExchange<dim>::remember(const std::vector<ExchangePair<dim>> &pairs,
                                      const std::vector<Tensor<1, dim>> &impulse_on_a)
{
  // ContactPairs lists the pairs in ascending key order, so the keys stay sorted for
  // warm_start()'s binary search.
  last_keys.resize(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i)
    last_keys[i] = pairs[i].key;
  Assert(std::is_sorted(last_keys.begin(), last_keys.end()),
         dealii::ExcMessage("contact pairs out of key order"));
  last_impulses = impulse_on_a;
}

namespace
{
template <int dim>
bool settled(const std::vector<Tensor<1, dim>> &before,
             const std::vector<Tensor<1, dim>> &after, const double tolerance)
{
  double change = 0, largest = 0;
  for (std::size_t i = 0; i < after.size(); ++i)
  {
    change  = std::max(change, (after[i] - before[i]).norm());
    largest = std::max(largest, after[i].norm());
  }
  return change <= tolerance * largest;
}
} // namespace

template <int dim>
void ProjectedExchange<dim>::apply(
    const std::vector<ExchangePair<dim>> &pairs, GridTransfer<dim> &transfer,
    const ParticleStore<dim> &particles, const std::vector<std::uint8_t> &touches,
    std::vector<Tensor<1, dim>> &velocity, std::vector<Tensor<1, dim>> &impulse_on_a,
    const unsigned int sweeps, const double tolerance, const double mass_tolerance)
{
  sweeps_done                   = 0;
  NodalFields<dim> &nodes       = transfer.nodes();
  const Connectivity<dim> &conn = transfer.connectivity();
  const std::size_t n_fields    = nodes.mass.size();
  jump.resize(n_fields);
  response.resize(n_fields);
  scale.resize(n_fields);
  in_pair.assign(n_fields, 0);
  delta.resize(particles.size());
  impulse_on_a.assign(pairs.size(), Tensor<1, dim>());
  const bool warm = warm_start(pairs, impulse_on_a);
  next.resize(pairs.size());
  if (pairs.empty())
  {
    remember(pairs, impulse_on_a);
    return;
  }
  // The sweeps visit only the particles near contact, listed once.
  touching.clear();
  for (std::size_t p = 0; p < particles.size(); ++p)
    if (touches[p])
      touching.push_back(p);
  for (const auto &q : pairs)
  {
    in_pair[q.a] = !q.fixed_a;
    in_pair[q.b] = !q.fixed_b;
    scale[q.a] = scale[q.b] = 0;
  }
  // A field's response to a unit jump of every pair field of its body: the share of
  // the jump its particles carry back to it.
  transfer.scatter(
      [&](const std::size_t p)
      {
        if (!touches[p])
          return;
        const std::size_t o = p * conn.stride;
        double share        = 0;
        for (unsigned int k = 0; k < conn.n_nodes[p]; ++k)
          if (in_pair[conn.nodes[o + k]])
            share += conn.N[o + k];
        if (share == 0)
          return;
        for (unsigned int k = 0; k < conn.n_nodes[p]; ++k)
          if (in_pair[conn.nodes[o + k]])
            scale[conn.nodes[o + k]] += conn.N[o + k] * particles.mass[p] * share;
      });
  for (const auto &q : pairs)
    for (const unsigned int F : {q.a, q.b})
      if (in_pair[F])
        // A floor against a field whose particles barely reach its pair fields.
        scale[F] = std::max(scale[F] / nodes.mass[F], 1e-3);

  const std::vector<Tensor<1, dim>> &rate = nodes.rate;
  for (unsigned int sweep = 0; sweep < sweeps; ++sweep)
  {
    if (sweep > 0 || warm)
      respond(pairs, transfer, particles, touches, impulse_on_a);
    for (std::size_t i = 0; i < pairs.size(); ++i)
    {
      const auto &q     = pairs[i];
      Tensor<1, dim> ra = rate[q.a], rb = rate[q.b];
      if (sweep > 0 || warm)
      {
        if (in_pair[q.a])
          ra += response[q.a] / nodes.mass[q.a];
        if (in_pair[q.b])
          rb += response[q.b] / nodes.mass[q.b];
      }
      const Tensor<1, dim> dv = ra - rb;
      const double vn         = dv * q.normal;
      const Tensor<1, dim> vt = dv - vn * q.normal;
      const double k          = (q.fixed_a ? 0.0 : scale[q.a] / nodes.mass[q.a]) +
                       (q.fixed_b ? 0.0 : scale[q.b] / nodes.mass[q.b]);
      const Tensor<1, dim> &J = impulse_on_a[i];
      const double jn         = -(J * q.normal);
      const Tensor<1, dim> jt = J + jn * q.normal;
      // Push while the projected rates approach, never pull.
      const double jn_new   = std::max(0.0, jn + vn / k);
      Tensor<1, dim> jt_new = jt - vt / k;
      const double cap = q.friction * jn_new, size = jt_new.norm();
      if (size > cap)
        jt_new *= size > 0 ? cap / size : 0.0;
      next[i] = jt_new - jn_new * q.normal;
    }
    // Converged once no impulse changes by more than the tolerance's share of the
    // largest: the rates then approach by at most that share of what was removed.
    const bool converged = settled(impulse_on_a, next, tolerance);
    std::swap(next, impulse_on_a);
    ++sweeps_done;
    if (converged)
      break;
  }
  respond(pairs, transfer, particles, touches, impulse_on_a);
  remember(pairs, impulse_on_a);
  for (const std::size_t p : touching)
  {
    velocity[p] += delta[p];
    const std::size_t o = p * conn.stride;
    for (unsigned int k = 0; k < conn.n_nodes[p]; ++k)
    {
      const unsigned int F = conn.nodes[o + k];
      // Each field once: the response is cleared once it is applied.
      if (response[F] == Tensor<1, dim>())
        continue;
      nodes.momentum[F] += response[F];
      if (nodes.mass[F] > mass_tolerance)
        nodes.rate[F] += response[F] / nodes.mass[F];
      response[F] = Tensor<1, dim>();
    }
  }
}

template class ProjectedExchange<2>;
template class ProjectedExchange<3>;
} // namespace lme_mpm
