#ifndef LME_MPM_CONTACT_BODY_FIELDS_H
#define LME_MPM_CONTACT_BODY_FIELDS_H

#include <deal.II/base/tensor.h>

#include <lme_mpm/geometry/bodies.h>
#include <lme_mpm/grid/background_grid.h>
#include <lme_mpm/grid/field_layout.h>
#include <lme_mpm/particles/particle_store.h>
#include <lme_mpm/shape_functions/shape_function.h>

#include <array>
#include <cstdint>
#include <vector>

namespace lme_mpm
{
/**
 * A velocity field per body where the supports of several bodies may meet
 * (Bardenhagen et al. 2000): every step, the cells the bodies' particles occupy,
 * widened by the farthest a support reaches, mark the nodes each body may reach; a
 * node two or more bodies reach gets an extra field per body beyond the lowest (a
 * FieldLayout field tagged with the body's index), and the particle-node pairs there
 * go to their body's field. A node one body alone reaches keeps one field and costs
 * nothing extra. The prescribed bodies' fields are imposed here too.
 */
template <int dim>
class BodyFields
{
public:
  BodyFields(const BackgroundGrid<dim> &grid, const Bodies<dim> &bodies);

  /**
   * @p active: fields per body at all (multi-field contact, two bodies or more);
   * @p reach bounds the distance from a particle to a node of its support.
   */
  void set_up(bool active, double reach);
  bool active() const { return is_active; }

  /**
   * Finds the nodes that two bodies' supports may share (from the particles' cells,
   * which must be sorted) and gives each such node a field per body in @p layout.
   * Fields are never removed, so the layout only grows.
   */
  void assign_fields(const ParticleStore<dim> &particles, FieldLayout &layout);
  /**
   * Sends the particle-node pairs of [begin, end) at shared nodes to the field of the
   * particle's body, and flags the particles that have such a pair. Thread-safe per
   * range.
   */
  void separate(Connectivity<dim> &conn, const ParticleStore<dim> &particles,
                std::size_t begin, std::size_t end);

  /**
   * The field body @p body has at grid node @p I this step: I itself where the node
   * is not shared or the body is the lowest there, its extra field otherwise, and
   * FieldLayout::invalid where the body cannot reach the node. Call after
   * assign_fields().
   */
  unsigned int field_of_body(unsigned int I, unsigned int body) const;
  /// Calls f(field, body) for every body's field at shared node @p I.
  template <class F>
  void for_each_body_field(unsigned int I, const F &f) const
  {
    const std::uint32_t m = node_bodies[I];
    f(I, lowest_bit(m));
    for (std::uint32_t rest = m & (m - 1); rest != 0; rest &= rest - 1)
    {
      const unsigned int b = lowest_bit(rest);
      f(layout->find(I, b), b);
    }
  }
  /// The bodies that may reach grid node @p I this step, as a bit set.
  std::uint32_t bodies_at(const unsigned int I) const { return node_bodies[I]; }
  /// Nodes that carry more than one body's field this step, ascending.
  const std::vector<unsigned int> &shared_nodes() const { return shared; }
  /// Per particle: 1 if a node of its support is shared (set by separate()).
  const std::vector<std::uint8_t> &touches_shared() const { return touches; }

  /// The prescribed bodies' velocities at @p t on their fields (those with mass).
  void impose_prescribed_rates(std::vector<Tensor<1, dim>> &x,
                               const std::vector<double> &mass, double t) const;
  /// Their time derivatives (central difference of half-width @p h) at @p t.
  void impose_prescribed_accelerations(std::vector<Tensor<1, dim>> &x,
                                       const std::vector<double> &mass, double t,
                                       double h) const;

  static unsigned int lowest_bit(const std::uint32_t m)
  {
    return static_cast<unsigned int>(__builtin_ctz(m));
  }

private:
  struct PrescribedField
  {
    unsigned int field, body, node;
  };
  /// Marks the nodes the particles of each occupied cell can reach with their bodies.
  void mark_reached_nodes(const ParticleStore<dim> &particles);

  const BackgroundGrid<dim> &grid;
  const Bodies<dim> &bodies;
  bool is_active = false;
  // Per direction and cell index: the first and last node a particle in that cell
  // can reach.
  std::array<std::vector<unsigned int>, dim> reach_lo, reach_hi;
  // This step: per grid node the bit set of bodies that may reach it, the nodes with
  // any bit, the nodes with two or more, the prescribed bodies' fields.
  const FieldLayout *layout = nullptr;
  std::vector<std::uint32_t> node_bodies;
  std::vector<unsigned int> marked, shared;
  // The particles' cells and bodies the marks were made from (mark_reached_nodes()).
  std::vector<std::uint32_t> marked_cells;
  std::vector<std::uint16_t> marked_bodies;
  bool marks_valid = false;
  std::vector<PrescribedField> prescribed_fields;
  std::vector<std::uint8_t> touches;
};
} // namespace lme_mpm

#endif
