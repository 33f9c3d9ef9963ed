#ifndef LME_MPM_CONTACT_BODY_CONTACT_H
#define LME_MPM_CONTACT_BODY_CONTACT_H

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/parsed_function.h>
#include <deal.II/base/tensor.h>

#include <lme_mpm/contact/projected_exchange.h>
#include <lme_mpm/grid/background_grid.h>
#include <lme_mpm/grid/field_layout.h>
#include <lme_mpm/particles/particle_store.h>
#include <lme_mpm/solver/explicit_newmark.h>
#include <lme_mpm/solver/grid_transfer.h>

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace lme_mpm
{
using namespace dealii;

/**
 * Contact between bodies on separate velocity fields (Bardenhagen et al. 2000, 2001),
 * and bodies that move as prescribed.
 *
 * Where the supports of two or more bodies may share a grid node, the node carries one
 * field per body (extra fields of the FieldLayout tagged with the body's index; the
 * lowest body keeps the node's own field), so every body has its own mass, momentum
 * and velocity there. Which nodes are shared is found every step from the cells the
 * bodies occupy, widened by the farthest a support reaches; a node one body alone
 * reaches keeps one field and costs nothing extra.
 *
 * At a shared node, two bodies are in contact when the particle volume the node sees,
 * sum_p N_Ip V_p over all bodies, fills a set fraction of the node's own volume (a
 * gap between the bodies leaves a hole in it: see doc/contact.md for how wide a gap
 * that is for each shape function). Bodies in contact that approach each other along
 * the contact normal (from the fields' volume gradients) exchange the momentum that
 * removes their normal relative velocity, with Coulomb friction on the tangential
 * part (a coefficient per pair of bodies); separating bodies move freely. The
 * exchange is applied to the displacement rates (positions, strains) and to the
 * accelerations, on the trial end-of-step velocity of the Newmark corrector (particle
 * velocities), in equal and opposite amounts: momentum is conserved to round-off.
 *
 * A body with a prescribed velocity (a ParsedFunction of x and t) is rigid and has
 * infinite mass in the exchange; the force it receives and the work it does on the
 * others are reported, and its particles are left out of the energies.
 */
template <int dim>
class BodyContact
{
public:
  BodyContact(const BackgroundGrid<dim> &grid, GridTransfer<dim> &transfer,
              ParticleStore<dim> &particles);

  /// Declares "Contact" and each "Body N/Name" and "Body N/Prescribed velocity".
  static void declare_parameters(ParameterHandler &prm, unsigned int n_bodies);
  /**
   * Reads the entries. @p reach bounds the distance from a particle to a node of its
   * support; @p reserved_names are names the history already uses (constraint sets).
   */
  void parse_parameters(ParameterHandler &prm, unsigned int n_bodies, double thickness,
                        double reach, const std::vector<std::string> &reserved_names);

  /// Multi-field contact with at least two bodies.
  bool active() const { return multi_field && n_bodies > 1; }
  bool any_prescribed() const { return n_prescribed > 0; }

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

  /**
   * Distributed runs: only the pairs at the nodes this rank owns (@p owned_nodes,
   * per grid node) count towards the bodies' contact forces and work, and
   * @p sum_over_ranks sums the forces over the ranks.
   */
  void set_distribution(const std::vector<std::uint8_t> *owned,
                        std::function<void(std::vector<double> &)> sum)
  {
    owned_nodes    = owned;
    sum_over_ranks = std::move(sum);
  }
  /// Per body: 1 if it moves as prescribed.
  const std::vector<std::uint8_t> &prescribed_bodies() const { return prescribed; }
  const std::string &name(const unsigned int body) const { return names[body]; }
  const std::vector<std::string> &body_names() const { return names; }

  /**
   * Finds the nodes that two bodies' supports may share (from the particles' cells,
   * which must be sorted) and gives each such node a field per body in @p layout.
   * Fields are never removed, so the layout only grows.
   */
  void assign_fields(const ParticleStore<dim> &particles, FieldLayout &layout);
  /**
   * Sends the particle-node pairs of [begin, end) at shared nodes to the field of the
   * particle's body. Thread-safe per range.
   */
  void separate(Connectivity<dim> &conn, std::size_t begin, std::size_t end);

  /**
   * The field body @p body has at grid node @p I this step: I itself where the node
   * is not shared or the body is the lowest there, its extra field otherwise, and
   * FieldLayout::invalid where the body cannot reach the node. Call after
   * assign_fields().
   */
  unsigned int field_of_body(unsigned int I, unsigned int body) const;

  /// The prescribed bodies' velocities at @p t on their fields' rates.
  void impose_prescribed_rates(std::vector<Tensor<1, dim>> &x, double t) const;
  /// Their time derivatives (central difference of half-width @p h) at @p t.
  void impose_prescribed_accelerations(std::vector<Tensor<1, dim>> &x, double t,
                                       double h) const;

  /// Finds the pairs of fields in contact and exchanges momentum on the rates.
  /**
   * Finds the pairs in contact and exchanges momentum on the displacement rates: with
   * 'Exchange = projected' the step's whole exchange (the particles' velocities change
   * and the rates follow them; the force is recorded), with 'nodal' the rates alone.
   */
  void on_rates(double mass_tolerance, double dt);
  /**
   * 'nodal': the exchange on the accelerations, for the corrector's trial end-of-step
   * velocity. Records the contact force on every body ('projected': the force of the
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

  /// history.csv: force_<name>_x ... (with contact) and displacement_<name>_x ... per
  /// named body. The force is the mean over the steps since the previous row (the
  /// impulse over the elapsed time): the force of one step chatters as particles cross
  /// cells, its mean over an output interval is the load.
  void write_header(std::ostream &out) const;
  void write_row(std::ostream &out, const ParticleStore<dim> &particles);
  /// Per body: the contact force averaged over the interval the last history row
  /// closed, and the largest of these means' magnitudes so far.
  const std::vector<Tensor<1, dim>> &mean_forces() const { return mean_force; }
  const std::vector<double> &peak_forces() const { return peak_force; }
  /// Peak contact force magnitude per named body (the largest of the row means),
  /// for summary.json.
  void add_results(std::map<std::string, double> &results) const;

  template <class Archive>
  void serialize(Archive &ar)
  {
    ar(peak_force, stuck_pairs, impulse, impulse_time);
    mean_force.assign(n_bodies, Tensor<1, dim>());
    AssertThrow(peak_force.size() == n_bodies,
                ExcMessage("the checkpoint holds another number of bodies"));
  }

  /// Gives the particles of prescribed bodies their prescribed velocity at @p t (their
  /// initial velocity entry is not used).
  void set_prescribed_velocities(ParticleStore<dim> &store, double t) const;

  /// Nodes that carried more than one body's field in the last step.
  std::size_t n_shared_nodes() const { return shared_nodes.size(); }
  /// Pairs of fields in contact in the last step.
  std::size_t n_contact_pairs() const { return pairs.size(); }

private:
  struct Pair
  {
    unsigned int a, b; // fields
    unsigned int body_a, body_b;
    Tensor<1, dim> normal; // from a to b
    double friction;
    bool held; // stuck at the end of the last step
    std::uint64_t key;
  };
  struct PrescribedField
  {
    unsigned int field, body, node;
  };

  Tensor<1, dim> prescribed_velocity(unsigned int body, const Point<dim> &x,
                                     double t) const;
  /// Calls f(field, body) for every body's field at shared node I.
  template <class F>
  void for_each_body_field(unsigned int I, const F &f) const;
  /**
   * Changes x on every approaching pair so that the normal relative velocity
   * velocity(F) vanishes (Coulomb-limited tangentially); x changes the velocity by
   * @p scale times its own change. On the rates, pairs that stuck at the end of the
   * last step are held together tangentially. record(pair, impulse on a, stuck) sees
   * every pair.
   */
  template <class Velocity, class Record>
  void exchange(std::vector<Tensor<1, dim>> &x, const Velocity &velocity, double scale,
                bool rate_stage, const Record &record) const;

  /// Pairs in contact at the shared nodes, from this step's rates.
  void find_pairs(double mass_tolerance);
  /// 'nodal': the exchange on the corrector's trial velocities; records the forces,
  /// returns the prescribed bodies' work.
  double exchange_accelerations(const ExplicitNewmark &newmark, double dt);

  const BackgroundGrid<dim> &grid;
  GridTransfer<dim> &transfer;
  ParticleStore<dim> &particles;
  bool projected      = true;
  unsigned int sweeps = 8;
  double rate_work    = 0;
  ProjectedExchange<dim> projected_exchange;
  std::vector<ExchangePair<dim>> exchange_pairs;
  std::vector<Tensor<1, dim>> pair_impulse;

  bool multi_field         = false;
  unsigned int normal_rule = 1; // larger gradient, larger volume, difference
  unsigned int n_bodies = 0, n_prescribed = 0;
  double volume_fraction = 0.9, thickness = 1;
  std::vector<std::string> names;
  std::vector<std::uint8_t> prescribed;
  std::vector<std::unique_ptr<Functions::ParsedFunction<dim>>> velocity_functions;
  std::vector<std::string> velocity_entries;
  std::vector<std::uint8_t> constant_velocity;
  std::vector<Tensor<1, dim>> constant_value;
  /// friction[a * n_bodies + b]
  std::vector<double> friction;

  // Per direction and cell index: the first and last node a particle in that cell
  // can reach.
  std::array<std::vector<unsigned int>, dim> reach_lo, reach_hi;

  // This step: per grid node the bit set of bodies that may reach it, the nodes with
  // any bit, the nodes with two or more, the prescribed bodies' fields.
  const FieldLayout *layout = nullptr;
  std::vector<std::uint32_t> node_bodies;
  std::vector<unsigned int> marked_nodes, shared_nodes;
  std::vector<PrescribedField> prescribed_fields;
  std::vector<std::uint8_t> touches_shared;
  std::vector<Tensor<1, dim>> volume_gradient;
  std::vector<double> field_volume;
  std::vector<Pair> pairs;
  /// The pairs (grid node, bodies) that stuck at the end of the last step, sorted.
  std::vector<std::uint64_t> stuck_pairs;

  std::vector<Tensor<1, dim>> contact_force;
  const std::vector<std::uint8_t> *owned_nodes = nullptr;
  std::function<void(std::vector<double> &)> sum_over_ranks;
  /// True if pair field @p F's node is this rank's to report.
  bool reports(unsigned int F) const;
  /// Sums contact_force over the ranks.
  void sum_forces();
  std::vector<double> peak_force;
  /// Impulse per body and component since the last history row, and the time it
  /// covers.
  std::vector<double> impulse;
  double impulse_time = 0;
  std::vector<Tensor<1, dim>> mean_force;
};
} // namespace lme_mpm

#endif
