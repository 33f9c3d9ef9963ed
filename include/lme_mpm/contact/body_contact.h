#ifndef LME_MPM_CONTACT_BODY_CONTACT_H
#define LME_MPM_CONTACT_BODY_CONTACT_H

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <lme_mpm/base/rank_reductions.h>
#include <lme_mpm/contact/body_fields.h>
#include <lme_mpm/contact/contact_forces.h>
#include <lme_mpm/contact/contact_pairs.h>
#include <lme_mpm/contact/projected_exchange.h>
#include <lme_mpm/geometry/bodies.h>
#include <lme_mpm/solver/explicit_newmark.h>
#include <lme_mpm/solver/grid_transfer.h>

#include <map>
#include <string>
#include <vector>

namespace lme_mpm
{
/**
 * Contact between bodies on separate velocity fields (Bardenhagen et al. 2000, 2001),
 * stage by stage of the step: the fields per body (BodyFields), the pairs in contact
 * and their nodal exchange (ContactPairs), the projected exchange the particles carry
 * (ProjectedExchange, the default) and the forces each body receives (ContactForces).
 * Reads the "Contact" entries. Bodies that move as prescribed (Bodies) are rigid and
 * have infinite mass in the exchange; the force they receive and the work they do on
 * the others are reported. Momentum is exchanged in equal and opposite amounts, so it
 * is conserved to round-off.
 */
template <int dim>
class BodyContact
{
public:
  BodyContact(const BackgroundGrid<dim> &grid, GridTransfer<dim> &transfer,
              ParticleStore<dim> &particles, const Bodies<dim> &bodies);

  /// Declares "Contact".
  static void declare_parameters(ParameterHandler &prm);
  /**
   * Reads the entries; @p reach bounds the distance from a particle to a node of its
   * support. Throws ExcBadInput naming the entry, and when a body is prescribed
   * without multi-field contact (it could act on nothing).
   */
  void parse_parameters(ParameterHandler &prm, double thickness, double reach);
  /// Distributed runs: forces are booked at the nodes this rank owns, then summed.
  void set_ranks(const RankReductions &ranks) { forces.set_ranks(ranks); }

  /// Multi-field contact with at least two bodies.
  bool active() const { return fields.active(); }
  /// The fields per body (for crack faces, whose near field one of them holds).
  const BodyFields<dim> &body_fields() const { return fields; }

  /**
   * How far one step's exchange reaches from a node through the particles (m), for
   * a distributed run's halo: the projected exchange passes node to particle to node
   * once per sweep, and once more for its response scale and its final response; the
   * nodal exchange carries which pairs stuck from one step to the next, decided from
   * nodes as far as a step reads (four support radii, and two for good measure).
   */
  double reach(const double support_radius) const
  {
    if (!active())
      return 0.0;
    return projected ? 2.0 * (sweeps + 2) * support_radius : 6.0 * support_radius;
  }

  /// Gives shared nodes a field per body (BodyFields::assign_fields).
  void assign_fields(const ParticleStore<dim> &p, FieldLayout &layout)
  {
    fields.assign_fields(p, layout);
  }
  /// Sends pairs at shared nodes to their body's field (BodyFields::separate).
  void separate(Connectivity<dim> &conn, const std::size_t begin, const std::size_t end)
  {
    fields.separate(conn, particles, begin, end);
  }
  /// The prescribed bodies' velocities at @p t on their fields' rates.
  void impose_prescribed_rates(std::vector<Tensor<1, dim>> &x, const double t) const
  {
    fields.impose_prescribed_rates(x, transfer.nodes().mass, t);
  }
  /// Their time derivatives (central difference of half-width @p h) at @p t.
  void impose_prescribed_accelerations(std::vector<Tensor<1, dim>> &x, const double t,
                                       const double h) const
  {
    fields.impose_prescribed_accelerations(x, transfer.nodes().mass, t, h);
  }

  /**
   * Finds the pairs in contact and exchanges momentum on the displacement rates: with
   * 'Exchange = projected' the step's whole exchange (the particles' velocities change
   * and the rates follow them; the force is recorded), with 'nodal' the rates alone.
   */
  void on_rates(double mass_tolerance, double dt);
  /**
   * 'nodal': the exchange on the accelerations, for the corrector's trial end-of-step
   * velocity. Books the contact force on every body ('projected': the force of the
   * exchange on the rates); returns the work the prescribed bodies did on the others
   * over the step.
   */
  double on_accelerations(const ExplicitNewmark &newmark, double dt);
  /**
   * At the start (rates = velocities): finds the pairs in contact and removes their
   * approaching relative normal acceleration, so that bodies resting on each other
   * do not start by falling into each other.
   */
  void on_initial_accelerations(double mass_tolerance);

  /// Per body: the contact force it received in the last step (N).
  const std::vector<Tensor<1, dim>> &step_forces() const { return forces.step(); }
  /// The number of shared nodes, for summary.json.
  void add_results(std::map<std::string, double> &results) const;

  template <class Archive>
  void serialize(Archive &ar)
  {
    pairs.serialize(ar);
    projected_exchange.serialize(ar);
  }

  /// Pairs of fields in contact in the last step.
  std::size_t n_contact_pairs() const { return pairs.size(); }

private:
  /// 'nodal': the exchange on the corrector's trial velocities; books the forces,
  /// returns the prescribed bodies' work.
  double exchange_accelerations(const ExplicitNewmark &newmark, double dt);
  /// 'projected': the exchange, its forces and the prescribed bodies' work.
  void exchange_projected(double mass_tolerance, double dt);

  const BackgroundGrid<dim> &grid;
  GridTransfer<dim> &transfer;
  ParticleStore<dim> &particles;
  const Bodies<dim> &bodies;
  BodyFields<dim> fields;
  ContactPairs<dim> pairs;
  ContactForces<dim> forces;
  bool projected      = true;
  unsigned int sweeps = 8;
  double tolerance    = 1e-4;
  /// Sweeps made and exchanges with pairs, for summary.json.
  unsigned long sweep_count = 0, exchange_count = 0;
  unsigned int max_sweeps_used = 0;
  double rate_work             = 0;
  ProjectedExchange<dim> projected_exchange;
  std::vector<ExchangePair<dim>> exchange_pairs;
  std::vector<Tensor<1, dim>> pair_impulse;
};
} // namespace lme_mpm

#endif
