#include <lme_mpm/base/input.h>
#include <lme_mpm/contact/contact_pairs.h>

#include <algorithm>
#include <cmath>

namespace lme_mpm
{
namespace
{
/// A pair of bodies at a grid node, ordered by node, then bodies.
std::uint64_t pair_key(const unsigned int node, const unsigned int a,
                       const unsigned int b)
{
  return (std::uint64_t(node) << 10) | (a << 5) | b;
}
} // namespace

template <int dim>
void ContactPairs<dim>::set_up(const BackgroundGrid<dim> &g, const std::string &normal,
                               const double fraction, const double mu,
                               const std::string &pair_friction, const unsigned int n,
                               const double thickness_in)
{
  grid            = &g;
  normal_rule     = normal == "larger gradient" ? 0 : normal == "larger volume" ? 1 : 2;
  volume_fraction = fraction;
  n_bodies        = n;
  thickness       = dim == 2 ? thickness_in : 1.0;
  friction.assign(n_bodies * n_bodies, mu);
  for (const auto &item : input::split(pair_friction, ';'))
  {
    const std::string entry = "Contact/Pair friction coefficients";
    const auto colon        = item.find(':');
    const auto dash         = item.find('-');
    AssertThrow(colon != std::string::npos && dash != std::string::npos && dash < colon,
                ExcBadInput(entry, "expected 'a-b: mu', got '" + item + "'"));
    const auto a  = input::parse_doubles(item.substr(0, dash), entry);
    const auto b  = input::parse_doubles(item.substr(dash + 1, colon - dash - 1), entry);
    const auto mu = input::parse_doubles(item.substr(colon + 1), entry);
    AssertThrow(a.size() == 1 && b.size() == 1 && mu.size() == 1,
                ExcBadInput(entry, "expected 'a-b: mu', got '" + item + "'"));
    for (const double body : {a[0], b[0]})
      AssertThrow(body >= 1 && body <= n_bodies && body == std::floor(body),
                  ExcBadInput(entry, "'" + item + "': bodies are numbered 1 to " +
                                         std::to_string(n_bodies)));
    AssertThrow(a[0] != b[0],
                ExcBadInput(entry, "'" + item + "' pairs a body with itself"));
    input::require_range(mu[0], 0, 1e3, false, entry);
    const unsigned int i = a[0] - 1, j = b[0] - 1;
    friction[i * n_bodies + j] = friction[j * n_bodies + i] = mu[0];
  }
}

template <int dim>
double ContactPairs<dim>::node_volume(const unsigned int I) const
{
  unsigned int rest = I;
  double volume     = thickness;
  for (int d = dim - 1; d >= 0; --d)
  {
    const unsigned int i = rest / grid->node_stride(d);
    rest -= i * grid->node_stride(d);
    // The node's share of its cells: half of each cell beside it (half a cell at a
    // grid face, where a full one would keep contact from ever starting).
    const auto &c      = grid->coordinates(d);
    const double below = i > 0 ? c[i] - c[i - 1] : 0.0;
    const double above = i + 1 < c.size() ? c[i + 1] - c[i] : 0.0;
    volume *= 0.5 * (below + above);
  }
  return volume;
}

template <int dim>
void ContactPairs<dim>::measure_volumes(const BodyFields<dim> &fields,
                                        const GridTransfer<dim> &transfer,
                                        const ParticleStore<dim> &particles)
{
  const NodalFields<dim> &nodes = transfer.nodes();
  const Connectivity<dim> &conn = transfer.connectivity();
  const FieldLayout &layout     = nodes.layout;
  const unsigned int n_grid     = layout.n_grid_nodes();
  volume_gradient.resize(nodes.mass.size());
  field_volume.resize(nodes.mass.size());
  for (const unsigned int I : fields.shared_nodes())
    fields.for_each_body_field(I,
                               [&](const unsigned int F, unsigned int)
                               {
                                 volume_gradient[F] = Tensor<1, dim>();
                                 field_volume[F]    = 0;
                               });
  // In the scatter's order (thread-count independent).
  const std::vector<std::uint8_t> &touches = fields.touches_shared();
  transfer.scatter(
      [&](const std::size_t p)
      {
        if (!touches[p])
          return;
        const std::size_t o = p * conn.stride;
        const double V      = particles.volume[p];
        for (unsigned int k = 0; k < conn.n_nodes[p]; ++k)
        {
          const unsigned int F = conn.nodes[o + k];
          if (layout.tag_of(F) == FieldLayout::crack_side)
            continue;
          const std::uint32_t bodies =
              fields.bodies_at(F < n_grid ? F : layout.node_of(F));
          if ((bodies & (bodies - 1)) == 0)
            continue;
          // d/dx_I sum_p V_p N(x_p - x_I): the gradient of the field's volume at
          // the node, pointing into its body (volume, not mass: bodies of different
          // densities weigh alike).
          volume_gradient[F] -= V * conn.grad_N[o + k];
          field_volume[F] += conn.N[o + k] * V;
        }
      });
}

template <int dim>
void ContactPairs<dim>::find(const BodyFields<dim> &fields, const Bodies<dim> &bodies,
                             const GridTransfer<dim> &transfer,
                             const ParticleStore<dim> &particles,
                             const double mass_tolerance)
{
  pairs.clear();
  if (!fields.active() || fields.shared_nodes().empty())
  {
    stuck_pairs.clear();
    return;
  }
  measure_volumes(fields, transfer, particles);
  const NodalFields<dim> &nodes = transfer.nodes();
  std::vector<std::pair<unsigned int, unsigned int>> present;
  for (const unsigned int I : fields.shared_nodes())
  {
    present.clear();
    double volume = 0;
    fields.for_each_body_field(I,
                               [&](const unsigned int F, const unsigned int b)
                               {
                                 if (nodes.mass[F] > mass_tolerance)
                                 {
                                   present.emplace_back(F, b);
                                   volume += field_volume[F];
                                 }
                               });
    if (present.size() < 2)
      continue;
    const double own = node_volume(I);
    if (volume < volume_fraction * own)
      continue;
    for (unsigned int i = 0; i < present.size(); ++i)
      for (unsigned int j = i + 1; j < present.size(); ++j)
      {
        const auto [a, ba] = present[i];
        const auto [b, bb] = present[j];
        if (bodies.prescribed(ba) && bodies.prescribed(bb))
          continue;
        // Both bodies must fill part of the node: the far tail of one body's support
        // carries a volume gradient that says little about where its surface is.
        if (std::min(field_volume[a], field_volume[b]) < 0.1 * own)
          continue;
        Tensor<1, dim> n;
        if (normal_rule == 0)
          n = volume_gradient[a].norm_square() >= volume_gradient[b].norm_square()
                  ? -volume_gradient[a]
                  : volume_gradient[b];
        else if (normal_rule == 1)
          n = field_volume[a] >= field_volume[b] ? -volume_gradient[a]
                                                 : volume_gradient[b];
        else
          n = volume_gradient[b] - volume_gradient[a];
        const double length = n.norm();
        if (!(length > 0))
          continue;
        const std::uint64_t key = pair_key(I, ba, bb);
        const bool held = std::binary_search(stuck_pairs.begin(), stuck_pairs.end(), key);
        pairs.push_back(
            {a, b, ba, bb, n / length, friction[ba * n_bodies + bb], held, key});
      }
  }
}

template class ContactPairs<2>;
template class ContactPairs<3>;
} // namespace lme_mpm
