#include <lme_mpm/base/format.h>
#include <lme_mpm/base/input.h>
#include <lme_mpm/base/parameters.h>
#include <lme_mpm/contact/body_contact.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <sstream>

namespace lme_mpm
{
namespace
{
/// The entries of "Contact", listed once for declaring and reading.
struct ContactEntries
{
  std::string type, normal, pairs, exchange;
  double friction = 0, volume_fraction = 0.9;
  unsigned int sweeps = 8;

  void entries(EntryList &list)
  {
    list.add("Type", type, "none", Patterns::Selection("none|multi-field"),
             "'none': all bodies share one velocity field (they stick where their "
             "supports overlap); 'multi-field': each body has its own field where "
             "supports of several bodies meet, with contact and friction between them "
             "(doc/contact.md).");
    list.add("Friction coefficient", friction, "0", Patterns::Double(0),
             "Coulomb friction coefficient of every pair of bodies in contact (0: "
             "frictionless), unless 'Pair friction coefficients' gives the pair one.");
    list.add("Pair friction coefficients", pairs, "", Patterns::Anything(),
             "Friction per pair of bodies, 'a-b: mu' separated by ';', with a and b "
             "the numbers N of 'Body N' (for example '1-2: 0.3; 2-3: 0').");
    list.add("Normal", normal, "larger volume",
             Patterns::Selection("larger gradient|larger volume|difference"),
             "Contact normal at a node, from the gradients of the bodies' particle "
             "volume sum_p V_p N_Ip: 'larger volume': the gradient of the body with "
             "more volume at the node (the body the node lies in; Nairn 2013 compares "
             "such choices); 'larger gradient': the gradient of larger magnitude; "
             "'difference': along the difference of the two gradients (symmetric, but "
             "tilted at a body's corners, where it drags a sliding body).");
    list.add("Exchange", exchange, "projected", Patterns::Selection("projected|nodal"),
             "How bodies in contact exchange momentum. 'projected': once a step, as a "
             "velocity jump the particles carry, found so that the displacement rates "
             "projected from the particles' new velocities stop approaching; the "
             "rates that move the particles are the ones they carry. 'nodal': on the "
             "nodal rates (positions only) and again on the corrector's trial "
             "velocities (the particles); gains energy while bodies unload on fine "
             "grids (doc/contact.md).");
    list.add("Exchange sweeps", sweeps, "8", Patterns::Integer(1, 1000),
             "'projected' exchange: Jacobi sweeps over the contact pairs per step, "
             "each a pass over the particles near contact. In 1..1000.");
    list.add("Contact volume fraction", volume_fraction, "0.9", Patterns::Double(0),
             "Two bodies at a node are in contact when the particle volume the node "
             "sees, sum_p N_Ip V_p over both, is at least this fraction of the node's "
             "own volume (a gap between them leaves that volume short). In (0, 1.5].");
  }
};

/// A pair of bodies at a grid node, ordered by node, then bodies.
std::uint64_t pair_key(const unsigned int node, const unsigned int a,
                       const unsigned int b)
{
  return (std::uint64_t(node) << 10) | (a << 5) | b;
}

unsigned int lowest_bit(const std::uint32_t m)
{
  return static_cast<unsigned int>(__builtin_ctz(m));
}
} // namespace

template <int dim>
BodyContact<dim>::BodyContact(const BackgroundGrid<dim> &grid,
                              GridTransfer<dim> &transfer, ParticleStore<dim> &particles)
    : grid(grid), transfer(transfer), particles(particles)
{
}

template <int dim>
void BodyContact<dim>::declare_parameters(ParameterHandler &prm,
                                          const unsigned int n_bodies)
{
  prm.enter_subsection("Contact");
  {
    EntryList list(prm, EntryList::Mode::declare);
    ContactEntries().entries(list);
  }
  prm.leave_subsection();
  for (unsigned int b = 0; b < n_bodies; ++b)
  {
    prm.enter_subsection(input::subsection_name("Body", b));
    prm.declare_entry("Name", "", Patterns::Anything(),
                      "Name of the body in history.csv (force_<name>_x, "
                      "displacement_<name>_x, ...) and summary.json: letters, digits "
                      "or '_'. Empty: not reported.");
    prm.enter_subsection("Prescribed velocity");
    Functions::ParsedFunction<dim>::declare_parameters(prm, dim);
    prm.declare_entry("Function expression", "", Patterns::Anything(),
                      "Velocity (m/s) the body follows, a function of x, y, z and t "
                      "with one component per direction separated by ';'. Empty: the "
                      "body moves freely. A prescribed body is rigid; it needs "
                      "Contact/Type = multi-field.");
    prm.leave_subsection();
    prm.leave_subsection();
  }
}

template <int dim>
void BodyContact<dim>::parse_parameters(ParameterHandler &prm,
                                        const unsigned int n_bodies_in,
                                        const double thickness_in, const double reach,
                                        const std::vector<std::string> &reserved_names)
{
  n_bodies  = n_bodies_in;
  thickness = dim == 2 ? thickness_in : 1.0;
  ContactEntries in;
  prm.enter_subsection("Contact");
  {
    EntryList list(prm, EntryList::Mode::parse);
    in.entries(list);
  }
  prm.leave_subsection();
  multi_field = in.type == "multi-field";
  normal_rule = in.normal == "larger gradient" ? 0 : in.normal == "larger volume" ? 1 : 2;
  volume_fraction = in.volume_fraction;
  projected       = in.exchange == "projected";
  sweeps          = in.sweeps;
  input::require_range(in.friction, 0, 1e3, false, "Contact/Friction coefficient");
  input::require_range(volume_fraction, 0, 1.5, false, "Contact/Contact volume fraction");
  AssertThrow(volume_fraction > 0,
              ExcBadInput("Contact/Contact volume fraction", "must be positive"));
  AssertThrow(!multi_field || n_bodies <= 32,
              ExcBadInput("Problem/Number of bodies",
                          "multi-field contact handles at most 32 bodies, not " +
                              std::to_string(n_bodies)));

  friction.assign(n_bodies * n_bodies, in.friction);
  for (const auto &item : input::split(in.pairs, ';'))
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

  names.assign(n_bodies, "");
  prescribed.assign(n_bodies, 0);
  velocity_functions.clear();
  velocity_functions.resize(n_bodies);
  velocity_entries.assign(n_bodies, "");
  constant_velocity.assign(n_bodies, 0);
  constant_value.assign(n_bodies, Tensor<1, dim>());
  n_prescribed = 0;
  for (unsigned int b = 0; b < n_bodies; ++b)
  {
    const std::string section = input::subsection_name("Body", b);
    prm.enter_subsection(section);
    names[b] = input::trim(prm.get("Name"));
    prm.enter_subsection("Prescribed velocity");
    const std::string expr = input::trim(prm.get("Function expression"));
    prm.leave_subsection();
    if (!expr.empty())
    {
      velocity_entries[b]   = section + "/Prescribed velocity";
      velocity_functions[b] = std::make_unique<Functions::ParsedFunction<dim>>(dim);
      input::parse_function(prm, "Prescribed velocity", *velocity_functions[b],
                            velocity_entries[b]);
      prescribed[b] = 1;
      ++n_prescribed;
      if (!input::depends_on_space_or_time(expr))
      {
        constant_value[b]    = prescribed_velocity(b, Point<dim>(), 0);
        constant_velocity[b] = 1;
      }
      else
        (void)prescribed_velocity(b, Point<dim>(), 0);
    }
    prm.leave_subsection();

    const std::string &n = names[b];
    AssertThrow(
        std::all_of(n.begin(), n.end(),
                    [](const char c)
                    { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }),
        ExcBadInput(section + "/Name", "'" + n + "' must be letters, digits or '_'"));
    if (n.empty())
      continue;
    for (unsigned int o = 0; o < b; ++o)
      AssertThrow(names[o] != n,
                  ExcBadInput(section + "/Name", "'" + n + "' is also the name of " +
                                                     input::subsection_name("Body", o)));
    for (const auto &r : reserved_names)
      AssertThrow(r != n, ExcBadInput(section + "/Name",
                                      "'" + n +
                                          "' is also the name of a constraint "
                                          "set (history.csv columns would clash)"));
  }
  AssertThrow(n_prescribed == 0 || multi_field,
              ExcBadInput("Contact/Type",
                          "a body has a prescribed velocity; it acts on the others "
                          "through contact only: set Contact/Type = multi-field"));
  AssertThrow(n_prescribed < n_bodies || n_bodies == 0,
              ExcBadInput("Body 1/Prescribed velocity",
                          "every body is prescribed: nothing is left to compute"));

  // The nodes a particle in cell i can reach along each direction: those within the
  // support radius of the cell (with a round-off margin).
  for (unsigned int d = 0; d < dim; ++d)
  {
    const auto &c          = grid.coordinates(d);
    const unsigned int n_c = c.size() - 1;
    const double margin    = 1e-9 * (c.back() - c.front());
    reach_lo[d].resize(n_c);
    reach_hi[d].resize(n_c);
    for (unsigned int i = 0; i < n_c; ++i)
    {
      const auto lo  = std::lower_bound(c.begin(), c.end(), c[i] - reach - margin);
      const auto hi  = std::upper_bound(c.begin(), c.end(), c[i + 1] + reach + margin);
      reach_lo[d][i] = static_cast<unsigned int>(lo - c.begin());
      reach_hi[d][i] = static_cast<unsigned int>(hi - c.begin()) - 1;
    }
  }
  contact_force.assign(n_bodies, Tensor<1, dim>());
  peak_force.assign(n_bodies, 0.0);
  impulse.assign(n_bodies * dim, 0.0);
  mean_force.assign(n_bodies, Tensor<1, dim>());
}

template <int dim>
Tensor<1, dim> BodyContact<dim>::prescribed_velocity(const unsigned int b,
                                                     const Point<dim> &x,
                                                     const double t) const
{
  if (constant_velocity[b])
    return constant_value[b];
  auto &f = *velocity_functions[b];
  f.set_time(t);
  Tensor<1, dim> v;
  for (unsigned int d = 0; d < dim; ++d)
  {
    v[d] = f.value(x, d);
    if (!std::isfinite(v[d]))
    {
      std::ostringstream msg;
      msg << "component "
          << "xyz"[d] << " is " << v[d] << " at " << point_to_string(x) << ", t = " << t
          << " s";
      AssertThrow(false, ExcBadInput(velocity_entries[b], msg.str()));
    }
  }
  return v;
}

template <int dim>
void BodyContact<dim>::set_prescribed_velocities(ParticleStore<dim> &store,
                                                 const double t) const
{
  if (n_prescribed == 0)
    return;
  for (std::size_t p = 0; p < store.size(); ++p)
    if (prescribed[store.body_id[p]])
      store.velocity[p] = prescribed_velocity(store.body_id[p], store.position[p], t);
}

template <int dim>
void BodyContact<dim>::assign_fields(const ParticleStore<dim> &store,
                                     FieldLayout &field_layout)
{
  layout = &field_layout;
  touches_shared.assign(store.size(), 0);
  if (!active())
    return;
  node_bodies.resize(grid.n_nodes(), 0);
  for (const unsigned int I : marked_nodes)
    node_bodies[I] = 0;
  marked_nodes.clear();
  shared_nodes.clear();
  prescribed_fields.clear();

  // Every occupied cell marks the nodes its particles can reach with their bodies.
  const auto &offsets        = store.cell_offsets();
  const unsigned int n_cells = offsets.size() - 1;
  std::array<unsigned int, dim> n_in;
  for (unsigned int d = 0; d < dim; ++d)
    n_in[d] = grid.coordinates(d).size() - 1;
  for (unsigned int c = 0; c < n_cells; ++c)
  {
    if (offsets[c] == offsets[c + 1])
      continue;
    std::uint32_t bodies = 0;
    for (std::size_t p = offsets[c]; p < offsets[c + 1]; ++p)
      bodies |= std::uint32_t(1) << store.body_id[p];
    std::array<unsigned int, dim> ijk, lo, hi, node;
    unsigned int rest = c;
    for (unsigned int d = 0; d < dim; ++d)
    {
      ijk[d] = rest % n_in[d];
      rest /= n_in[d];
      lo[d] = reach_lo[d][ijk[d]];
      hi[d] = reach_hi[d][ijk[d]];
    }
    node = lo;
    while (true)
    {
      const unsigned int I = grid.node_index(node);
      if (node_bodies[I] == 0)
        marked_nodes.push_back(I);
      node_bodies[I] |= bodies;
      unsigned int d = 0;
      while (d < dim && ++node[d] > hi[d])
        node[d] = lo[d], ++d;
      if (d == dim)
        break;
    }
  }
  std::sort(marked_nodes.begin(), marked_nodes.end());
  for (const unsigned int I : marked_nodes)
  {
    const std::uint32_t m = node_bodies[I];
    if ((m & (m - 1)) != 0)
    {
      shared_nodes.push_back(I);
      for (std::uint32_t rest = m & (m - 1); rest != 0; rest &= rest - 1)
        field_layout.add(I, lowest_bit(rest));
    }
    if (n_prescribed > 0)
      for (std::uint32_t rest = m; rest != 0; rest &= rest - 1)
      {
        const unsigned int b = lowest_bit(rest);
        if (prescribed[b])
          prescribed_fields.push_back(
              {b == lowest_bit(m) ? I : field_layout.find(I, b), b, I});
      }
  }
}

template <int dim>
void BodyContact<dim>::separate(Connectivity<dim> &conn, const std::size_t begin,
                                const std::size_t end)
{
  if (!active())
    return;
  const unsigned int n_grid          = layout->n_grid_nodes();
  std::vector<std::uint8_t> &touched = touches_shared;
  for (std::size_t p = begin; p < end; ++p)
  {
    const unsigned int body = particles.body_id[p];
    const std::size_t o     = p * conn.stride;
    std::uint8_t t          = 0;
    for (unsigned int k = 0; k < conn.n_nodes[p]; ++k)
    {
      const unsigned int I = conn.nodes[o + k];
      if (I >= n_grid) // a crack's second field: stays with the cracked body
        continue;
      const std::uint32_t m = node_bodies[I];
      AssertThrow(
          m & (std::uint32_t(1) << body),
          ExcMessage("a support reaches past the shape function's support radius: "
                     "contact cannot give this particle its body's field"));
      if ((m & (m - 1)) == 0)
        continue;
      t = 1;
      if (lowest_bit(m) != body)
        conn.nodes[o + k] = layout->find(I, body);
    }
    touched[p] = t;
  }
}

template <int dim>
template <class F>
void BodyContact<dim>::for_each_body_field(const unsigned int I, const F &f) const
{
  const std::uint32_t m = node_bodies[I];
  f(I, lowest_bit(m));
  for (std::uint32_t rest = m & (m - 1); rest != 0; rest &= rest - 1)
  {
    const unsigned int b = lowest_bit(rest);
    f(layout->find(I, b), b);
  }
}

template <int dim>
unsigned int BodyContact<dim>::field_of_body(const unsigned int I,
                                             const unsigned int body) const
{
  if (!active())
    return I;
  const std::uint32_t m = node_bodies[I];
  if ((m & (std::uint32_t(1) << body)) == 0)
    return FieldLayout::invalid;
  return lowest_bit(m) == body ? I : layout->find(I, body);
}

template <int dim>
void BodyContact<dim>::impose_prescribed_rates(std::vector<Tensor<1, dim>> &x,
                                               const double t) const
{
  const std::vector<double> &mass = transfer.nodes().mass;
  for (const auto &pf : prescribed_fields)
    if (mass[pf.field] != 0)
      x[pf.field] = prescribed_velocity(pf.body, grid.node_point(pf.node), t);
}

template <int dim>
void BodyContact<dim>::impose_prescribed_accelerations(std::vector<Tensor<1, dim>> &x,
                                                       const double t,
                                                       const double h) const
{
  const std::vector<double> &mass = transfer.nodes().mass;
  for (const auto &pf : prescribed_fields)
    if (mass[pf.field] != 0)
    {
      if (constant_velocity[pf.body])
        x[pf.field] = Tensor<1, dim>();
      else
      {
        const Point<dim> X = grid.node_point(pf.node);
        x[pf.field]        = (prescribed_velocity(pf.body, X, t + h) -
                       prescribed_velocity(pf.body, X, t - h)) /
                      (2 * h);
      }
    }
}

template <int dim>
void BodyContact<dim>::on_rates(const double mass_tolerance, const double dt)
{
  find_pairs(mass_tolerance);
  std::vector<Tensor<1, dim>> &rate = transfer.nodes().rate;
  if (!projected)
  {
    exchange(
        rate, [&](const unsigned int F) { return rate[F]; }, 1.0, true,
        [](const Pair &, const Tensor<1, dim> &, bool) {});
    return;
  }
  for (auto &f : contact_force)
    f = Tensor<1, dim>();
  rate_work = 0;
  stuck_pairs.clear();
  if (pairs.empty())
  {
    sum_forces();
    return;
  }
  exchange_pairs.clear();
  for (const Pair &q : pairs)
    exchange_pairs.push_back({q.a, q.b, prescribed[q.body_a] != 0,
                              prescribed[q.body_b] != 0, q.normal, q.friction});
  projected_exchange.apply(exchange_pairs, transfer, particles, touches_shared,
                           particles.velocity, pair_impulse, sweeps, mass_tolerance);
  for (std::size_t i = 0; i < pairs.size(); ++i)
  {
    const Pair &q = pairs[i];
    if (!reports(q.a))
      continue;
    const Tensor<1, dim> force = pair_impulse[i] / dt;
    contact_force[q.body_a] += force;
    contact_force[q.body_b] -= force;
    // A prescribed body moves its side of the contact at its imposed rate.
    if (prescribed[q.body_b])
      rate_work += pair_impulse[i] * rate[q.b];
    if (prescribed[q.body_a])
      rate_work -= pair_impulse[i] * rate[q.a];
  }
  sum_forces();
}

template <int dim>
bool BodyContact<dim>::reports(const unsigned int F) const
{
  return !owned_nodes || (*owned_nodes)[transfer.nodes().layout.node_of(F)];
}

template <int dim>
void BodyContact<dim>::sum_forces()
{
  if (!sum_over_ranks)
    return;
  std::vector<double> v;
  for (const auto &f : contact_force)
    for (unsigned int d = 0; d < dim; ++d)
      v.push_back(f[d]);
  sum_over_ranks(v);
  for (unsigned int b = 0; b < contact_force.size(); ++b)
    for (unsigned int d = 0; d < dim; ++d)
      contact_force[b][d] = v[b * dim + d];
}

template <int dim>
void BodyContact<dim>::find_pairs(const double mass_tolerance)
{
  pairs.clear();
  if (!active() || shared_nodes.empty())
  {
    stuck_pairs.clear();
    return;
  }
  const NodalFields<dim> &nodes = transfer.nodes();
  const Connectivity<dim> &conn = transfer.connectivity();
  const unsigned int n_grid     = layout->n_grid_nodes();
  volume_gradient.resize(nodes.mass.size());
  field_volume.resize(nodes.mass.size());
  for (const unsigned int I : shared_nodes)
    for_each_body_field(I,
                        [&](const unsigned int F, unsigned int)
                        {
                          volume_gradient[F] = Tensor<1, dim>();
                          field_volume[F]    = 0;
                        });
  // Mass gradient and particle volume of every body's field at the shared nodes, in
  // the scatter's order (thread-count independent).
  transfer.scatter(
      [&](const std::size_t p)
      {
        if (!touches_shared[p])
          return;
        const std::size_t o = p * conn.stride;
        const double V      = particles.volume[p];
        for (unsigned int k = 0; k < conn.n_nodes[p]; ++k)
        {
          const unsigned int F = conn.nodes[o + k];
          if (layout->tag_of(F) == FieldLayout::crack_side)
            continue;
          const std::uint32_t bodies = node_bodies[F < n_grid ? F : layout->node_of(F)];
          if ((bodies & (bodies - 1)) == 0)
            continue;
          // d/dx_I sum_p V_p N(x_p - x_I): the gradient of the field's volume at
          // the node, pointing into its body (volume, not mass: bodies of different
          // densities weigh alike).
          volume_gradient[F] -= V * conn.grad_N[o + k];
          field_volume[F] += conn.N[o + k] * V;
        }
      });

  std::vector<std::pair<unsigned int, unsigned int>> present;
  for (const unsigned int I : shared_nodes)
  {
    present.clear();
    double volume = 0;
    for_each_body_field(I,
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
    std::array<unsigned int, dim> ijk;
    unsigned int rest  = I;
    double node_volume = thickness;
    for (int d = dim - 1; d >= 0; --d)
    {
      ijk[d] = rest / grid.node_stride(d);
      rest -= ijk[d] * grid.node_stride(d);
      // The node's share of its cells: half of each cell beside it (half a cell at
      // a grid face, where a full one would keep contact from ever starting).
      const auto &c      = grid.coordinates(d);
      const double below = ijk[d] > 0 ? c[ijk[d]] - c[ijk[d] - 1] : 0.0;
      const double above = ijk[d] + 1 < c.size() ? c[ijk[d] + 1] - c[ijk[d]] : 0.0;
      node_volume *= 0.5 * (below + above);
    }
    if (volume < volume_fraction * node_volume)
      continue;
    for (unsigned int i = 0; i < present.size(); ++i)
      for (unsigned int j = i + 1; j < present.size(); ++j)
      {
        const auto [a, ba] = present[i];
        const auto [b, bb] = present[j];
        if (prescribed[ba] && prescribed[bb])
          continue;
        // Both bodies must fill part of the node: the far tail of one body's support
        // carries a volume gradient that says little about where its surface is.
        if (std::min(field_volume[a], field_volume[b]) < 0.1 * node_volume)
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

template <int dim>
double BodyContact<dim>::on_accelerations(const ExplicitNewmark &newmark, const double dt)
{
  // Every step counts towards the history row's mean force, with contact or not.
  impulse_time += dt;
  // The projected exchange happened on the rates; the step only books its force.
  const double work = projected ? rate_work : exchange_accelerations(newmark, dt);
  rate_work         = 0;
  for (unsigned int b = 0; b < n_bodies; ++b)
    for (unsigned int d = 0; d < dim; ++d)
      impulse[b * dim + d] += dt * contact_force[b][d];
  return work;
}

template <int dim>
double BodyContact<dim>::exchange_accelerations(const ExplicitNewmark &newmark,
                                                const double dt)
{
  for (auto &f : contact_force)
    f = Tensor<1, dim>();
  // This step's accelerations decide anew which pairs stick (pairs are in ascending
  // key order, so the list stays sorted).
  stuck_pairs.clear();
  if (pairs.empty())
  {
    sum_forces();
    return 0;
  }
  NodalFields<dim> &nodes = transfer.nodes();
  double work             = 0;
  const double scale      = newmark.gamma * dt;
  exchange(
      nodes.acceleration,
      [&](const unsigned int F)
      {
        return newmark.corrected_velocity(nodes.momentum[F] / nodes.mass[F],
                                          nodes.mass_acceleration[F] / nodes.mass[F],
                                          nodes.acceleration[F], dt);
      },
      scale, false,
      [&](const Pair &pair, const Tensor<1, dim> &impulse_on_a, const bool stuck)
      {
        if (stuck)
          stuck_pairs.push_back(pair.key);
        if (!reports(pair.a))
          return;
        // The force over the step that changes a's end velocity by impulse / m_a.
        const Tensor<1, dim> force = impulse_on_a / scale;
        contact_force[pair.body_a] += force;
        contact_force[pair.body_b] -= force;
        // A prescribed body moves its side of the contact at its imposed rate.
        if (prescribed[pair.body_b])
          work += dt * (force * nodes.rate[pair.b]);
        if (prescribed[pair.body_a])
          work -= dt * (force * nodes.rate[pair.a]);
      });
  sum_forces();
  return work;
}

template <int dim>
void BodyContact<dim>::on_initial_accelerations(const double mass_tolerance)
{
  find_pairs(mass_tolerance);
  std::vector<Tensor<1, dim>> &a = transfer.nodes().acceleration;
  exchange(
      a, [&](const unsigned int F) { return a[F]; }, 1.0, false,
      [](const Pair &, const Tensor<1, dim> &, bool) {});
}

template <int dim>
template <class Velocity, class Record>
void BodyContact<dim>::exchange(std::vector<Tensor<1, dim>> &x, const Velocity &velocity,
                                const double scale, const bool rate_stage,
                                const Record &record) const
{
  const std::vector<double> &mass = transfer.nodes().mass;
  for (const Pair &pair : pairs)
  {
    const Tensor<1, dim> dv = velocity(pair.a) - velocity(pair.b);
    const double vn         = dv * pair.normal;
    // A pair that stuck at the end of the last step keeps its fields together over
    // this step's displacement: its rates lose their tangential difference even
    // where the rates, interpolated from particles, no longer approach.
    const bool held = rate_stage && pair.held;
    if (!(vn > 0) && !held)
    {
      record(pair, Tensor<1, dim>(), false);
      continue; // separating or at rest along the normal
    }
    const double approach = std::max(vn, 0.0);
    const bool fixed_a = prescribed[pair.body_a], fixed_b = prescribed[pair.body_b];
    const double ma = mass[pair.a], mb = mass[pair.b];
    // Reduced mass of the pair; a prescribed side does not give way.
    const double mr         = fixed_b ? ma : fixed_a ? mb : ma * mb / (ma + mb);
    const Tensor<1, dim> vt = dv - vn * pair.normal;
    const double vt_norm    = vt.norm();
    // Stick if the tangential impulse stays within mu times the normal one.
    const bool stick                  = held || !(vt_norm > pair.friction * approach);
    const double slip                 = stick ? 1.0 : pair.friction * approach / vt_norm;
    const Tensor<1, dim> impulse_on_a = -mr * (approach * pair.normal + slip * vt);
    if (!fixed_a)
      x[pair.a] += impulse_on_a / (ma * scale);
    if (!fixed_b)
      x[pair.b] -= impulse_on_a / (mb * scale);
    // Only a frictional pair is held: a frictionless one has no tangential bond.
    record(pair, impulse_on_a, stick && approach > 0 && pair.friction > 0);
  }
}

template <int dim>
void BodyContact<dim>::write_header(std::ostream &out) const
{
  for (unsigned int b = 0; b < n_bodies; ++b)
  {
    if (names[b].empty())
      continue;
    if (active())
      for (unsigned int d = 0; d < dim; ++d)
        out << ",force_" << names[b] << "_"
            << "xyz"[d];
    for (unsigned int d = 0; d < dim; ++d)
      out << ",displacement_" << names[b] << "_"
          << "xyz"[d];
  }
}

template <int dim>
void BodyContact<dim>::write_row(std::ostream &out, const ParticleStore<dim> &store)
{
  // The mean since the last row (the first row has no step behind it).
  for (unsigned int b = 0; b < n_bodies; ++b)
  {
    Tensor<1, dim> mean = contact_force[b];
    if (impulse_time > 0)
      for (unsigned int d = 0; d < dim; ++d)
        mean[d] = impulse[b * dim + d] / impulse_time;
    mean_force[b] = mean;
    if (active())
      peak_force[b] = std::max(peak_force[b], mean.norm());
  }
  std::fill(impulse.begin(), impulse.end(), 0.0);
  impulse_time = 0;
  bool any     = false;
  for (const auto &n : names)
    any = any || !n.empty();
  if (!any)
    return;
  std::vector<Tensor<1, dim>> moment(n_bodies);
  std::vector<double> mass(n_bodies, 0.0);
  for (std::size_t p = 0; p < store.size(); ++p)
  {
    const unsigned int b = store.body_id[p];
    moment[b] += store.mass[p] * (store.position[p] - store.reference_position[p]);
    mass[b] += store.mass[p];
  }
  for (unsigned int b = 0; b < n_bodies; ++b)
  {
    if (names[b].empty())
      continue;
    if (active())
      for (unsigned int d = 0; d < dim; ++d)
        out << "," << mean_force[b][d];
    for (unsigned int d = 0; d < dim; ++d)
      out << "," << (mass[b] > 0 ? moment[b][d] / mass[b] : 0.0);
  }
}

template <int dim>
void BodyContact<dim>::add_results(std::map<std::string, double> &results) const
{
  if (!active())
    return;
  for (unsigned int b = 0; b < n_bodies; ++b)
    if (!names[b].empty())
      results["peak_contact_force_" + names[b]] = peak_force[b];
  results["contact_shared_nodes"] = shared_nodes.size();
}

template class BodyContact<2>;
template class BodyContact<3>;
} // namespace lme_mpm
