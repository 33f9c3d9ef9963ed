#include <lme_mpm/base/input.h>
#include <lme_mpm/base/parameters.h>
#include <lme_mpm/contact/body_contact.h>

#include <algorithm>

namespace lme_mpm
{
namespace
{
/// The entries of "Contact", listed once for declaring and reading.
struct ContactEntries
{
  std::string type, normal, pairs, exchange;
  double friction = 0, volume_fraction = 0.9, tolerance = 1e-4;
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
             "'projected' exchange: at most this many Jacobi sweeps over the contact "
             "pairs per step, each a pass over the particles near contact. In 1..1000.");
    list.add("Exchange tolerance", tolerance, "1e-4", Patterns::Double(0),
             "'projected' exchange: the sweeps stop once no pair's impulse changed in "
             "a sweep by more than this fraction of the largest. What an unfinished "
             "exchange leaves approaching is removed in the next step as an inelastic "
             "impact, which the energy balance shows as lost work. In [0, 1].");
    list.add("Contact volume fraction", volume_fraction, "0.9", Patterns::Double(0),
             "Two bodies at a node are in contact when the particle volume the node "
             "sees, sum_p N_Ip V_p over both, is at least this fraction of the node's "
             "own volume (a gap between them leaves that volume short). In (0, 1.5].");
  }
};

} // namespace

template <int dim>
BodyContact<dim>::BodyContact(const BackgroundGrid<dim> &grid,
                              GridTransfer<dim> &transfer, ParticleStore<dim> &particles,
                              const Bodies<dim> &bodies)
    : grid(grid), transfer(transfer), particles(particles), bodies(bodies),
      fields(grid, bodies)
{
}

template <int dim>
void BodyContact<dim>::declare_parameters(ParameterHandler &prm)
{
  prm.enter_subsection("Contact");
  {
    EntryList list(prm, EntryList::Mode::declare);
    ContactEntries().entries(list);
  }
  prm.leave_subsection();
}

template <int dim>
void BodyContact<dim>::parse_parameters(ParameterHandler &prm, const double thickness,
                                        const double reach)
{
  const unsigned int n_bodies = bodies.size();
  ContactEntries in;
  prm.enter_subsection("Contact");
  {
    EntryList list(prm, EntryList::Mode::parse);
    in.entries(list);
  }
  prm.leave_subsection();
  const bool multi_field = in.type == "multi-field";
  projected              = in.exchange == "projected";
  sweeps                 = in.sweeps;
  tolerance              = in.tolerance;
  input::require_range(in.tolerance, 0, 1, false, "Contact/Exchange tolerance");
  input::require_range(in.friction, 0, 1e3, false, "Contact/Friction coefficient");
  input::require_range(in.volume_fraction, 0, 1.5, false,
                       "Contact/Contact volume fraction");
  AssertThrow(in.volume_fraction > 0,
              ExcBadInput("Contact/Contact volume fraction", "must be positive"));
  AssertThrow(!multi_field || n_bodies <= 32,
              ExcBadInput("Problem/Number of bodies",
                          "multi-field contact handles at most 32 bodies, not " +
                              std::to_string(n_bodies)));
  pairs.set_up(grid, in.normal, in.volume_fraction, in.friction, in.pairs, n_bodies,
               thickness);
  AssertThrow(!bodies.any_prescribed_particles() || multi_field,
              ExcBadInput("Contact/Type",
                          "a body has a prescribed velocity; it acts on the others "
                          "through contact only: set Contact/Type = multi-field"));
  fields.set_up(multi_field && n_bodies > 1, reach);
  forces.reset(n_bodies);
}

template <int dim>
void BodyContact<dim>::on_rates(const double mass_tolerance, const double dt)
{
  pairs.find(fields, bodies, transfer, particles, mass_tolerance);
  std::vector<Tensor<1, dim>> &rate = transfer.nodes().rate;
  if (projected)
    exchange_projected(mass_tolerance, dt);
  else
    pairs.exchange(
        rate, transfer.nodes().mass, [&](const unsigned int F) { return rate[F]; }, 1.0,
        true, bodies, [](const auto &, const Tensor<1, dim> &, bool) {});
}

template <int dim>
void BodyContact<dim>::exchange_projected(const double mass_tolerance, const double dt)
{
  const std::vector<Tensor<1, dim>> &rate = transfer.nodes().rate;
  forces.clear();
  rate_work = 0;
  pairs.clear_stuck();
  if (pairs.empty())
  {
    forces.sum_over_ranks();
    return;
  }
  exchange_pairs.clear();
  for (const auto &q : pairs.list())
    exchange_pairs.push_back({q.a, q.b, bodies.prescribed(q.body_a),
                              bodies.prescribed(q.body_b), q.normal, q.friction, q.key});
  projected_exchange.apply(exchange_pairs, transfer, particles, fields.touches_shared(),
                           particles.velocity, pair_impulse, sweeps, tolerance,
                           mass_tolerance);
  sweep_count += projected_exchange.last_sweeps();
  ++exchange_count;
  max_sweeps_used           = std::max(max_sweeps_used, projected_exchange.last_sweeps());
  const FieldLayout &layout = transfer.nodes().layout;
  for (std::size_t i = 0; i < pairs.size(); ++i)
  {
    const auto &q = pairs.list()[i];
    if (!forces.reports(layout.node_of(q.a)))
      continue;
    forces.add(q.body_a, q.body_b, pair_impulse[i] / dt);
    // A prescribed body moves its side of the contact at its imposed rate.
    if (bodies.prescribed(q.body_b))
      rate_work += pair_impulse[i] * rate[q.b];
    if (bodies.prescribed(q.body_a))
      rate_work -= pair_impulse[i] * rate[q.a];
  }
  forces.sum_over_ranks();
}

template <int dim>
double BodyContact<dim>::on_accelerations(const ExplicitNewmark &newmark, const double dt)
{
  // The projected exchange happened on the rates; the step only books its force.
  const double work = projected ? rate_work : exchange_accelerations(newmark, dt);
  rate_work         = 0;
  return work;
}

template <int dim>
double BodyContact<dim>::exchange_accelerations(const ExplicitNewmark &newmark,
                                                const double dt)
{
  forces.clear();
  // This step's accelerations decide anew which pairs stick.
  pairs.clear_stuck();
  if (pairs.empty())
  {
    forces.sum_over_ranks();
    return 0;
  }
  NodalFields<dim> &nodes = transfer.nodes();
  double work             = 0;
  const double scale      = newmark.gamma * dt;
  pairs.exchange(
      nodes.acceleration, nodes.mass,
      [&](const unsigned int F) { return newmark.trial_velocity(nodes, F, dt); }, scale,
      false, bodies,
      [&](const auto &pair, const Tensor<1, dim> &impulse_on_a, const bool stuck)
      {
        if (stuck)
          pairs.add_stuck(pair);
        if (!forces.reports(nodes.layout.node_of(pair.a)))
          return;
        // The force over the step that changes a's end velocity by impulse / m_a.
        const Tensor<1, dim> force = impulse_on_a / scale;
        forces.add(pair.body_a, pair.body_b, force);
        // A prescribed body moves its side of the contact at its imposed rate.
        if (bodies.prescribed(pair.body_b))
          work += dt * (force * nodes.rate[pair.b]);
        if (bodies.prescribed(pair.body_a))
          work -= dt * (force * nodes.rate[pair.a]);
      });
  forces.sum_over_ranks();
  return work;
}

template <int dim>
void BodyContact<dim>::on_initial_accelerations(const double mass_tolerance)
{
  pairs.find(fields, bodies, transfer, particles, mass_tolerance);
  std::vector<Tensor<1, dim>> &a = transfer.nodes().acceleration;
  pairs.exchange(
      a, transfer.nodes().mass, [&](const unsigned int F) { return a[F]; }, 1.0, false,
      bodies, [](const auto &, const Tensor<1, dim> &, bool) {});
}

template <int dim>
void BodyContact<dim>::add_results(std::map<std::string, double> &results) const
{
  if (!active())
    return;
  results["contact_shared_nodes"] = fields.shared_nodes().size();
  if (projected && exchange_count > 0)
  {
    results["contact_mean_exchange_sweeps"] = double(sweep_count) / exchange_count;
    results["contact_max_exchange_sweeps"]  = max_sweeps_used;
  }
}

template class BodyContact<2>;
template class BodyContact<3>;
} // namespace lme_mpm
