#ifndef LME_MPM_BOUNDARY_NODE_CONSTRAINTS_H
#define LME_MPM_BOUNDARY_NODE_CONSTRAINTS_H

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/parsed_function.h>
#include <deal.II/base/tensor.h>

#include <lme_mpm/base/rank_reductions.h>
#include <lme_mpm/grid/background_grid.h>
#include <lme_mpm/grid/field_layout.h>

#include <array>
#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace lme_mpm
{
/**
 * An essential condition on a named set of grid nodes: selected velocity components
 * follow a ParsedFunction of (x, t) (0 for a fixed support, a ramp for displacement
 * control). The set comes from deal.II boundary ids of the grid and/or a box. The
 * constraint also accumulates what the output reports for the set: the reaction
 * (the force the constraint applies) and the imposed displacement. Every field of a
 * constrained node (a crack's second field, a body's field) is constrained with it.
 */
template <int dim>
class NodeConstraint
{
public:
  static void declare_parameters(ParameterHandler &prm);
  void parse_parameters(ParameterHandler &prm, const BackgroundGrid<dim> &grid,
                        const std::string &entry_prefix);
  const std::string &name() const { return set_name; }
  const std::vector<unsigned int> &nodes() const { return node_list; }
  bool constrains(const unsigned int c) const { return component_mask[c]; }
  /// Prescribed velocity of node i of the set at time t; throws ExcBadInput naming the
  /// entry where the expression is not finite.
  Tensor<1, dim> velocity(unsigned int i, double t) const;

  /**
   * Sets the constrained components of every field of the set's nodes in @p x to
   * value(i)[d] / divisor, with i the node's place in the set.
   */
  template <class Value>
  void impose(std::vector<Tensor<1, dim>> &x, const FieldLayout &layout,
              const Value &value, const double divisor) const
  {
    for (unsigned int i = 0; i < node_list.size(); ++i)
    {
      const Tensor<1, dim> v = value(i);
      const auto set         = [&](const unsigned int F)
      {
        for (unsigned int d = 0; d < dim; ++d)
          if (component_mask[d])
            x[F][d] = v[d] / divisor;
      };
      set(node_list[i]);
      layout.for_each_extra(node_list[i], set);
    }
  }

  /**
   * The reaction (M a - f on the set's fields, summed per node; M a from
   * @p mass_times_acceleration where the mass matrix is not lumped) and the imposed
   * displacement after a step with displacement rate @p rate. Returns the work of the
   * reaction over the step: the mean of the old and new reaction times the imposed
   * displacement increment (exact for the central-difference scheme), added to
   * @p work node by node. Only the nodes @p ranks says this rank owns count (all if
   * null): in a distributed run each rank sums its own, and finish_reaction() takes
   * the sum over the ranks.
   */
  void update_reaction(const FieldLayout &layout, const RankReductions *ranks,
                       const std::vector<double> &mass,
                       const std::vector<Tensor<1, dim>> &acceleration,
                       const std::vector<Tensor<1, dim>> &force,
                       const std::vector<Tensor<1, dim>> *mass_times_acceleration,
                       const std::vector<Tensor<1, dim>> &rate, double dt, double &work);

  /// Sets the step's reaction to @p reaction (summed over the ranks) and adds its
  /// impulse.
  void finish_reaction(const Tensor<1, dim> &reaction, double dt);

  /// Force the constraint applies (N), summed over the set.
  const Tensor<1, dim> &reaction() const { return total_reaction; }
  /// Mean imposed displacement of the set (m).
  const Tensor<1, dim> &displacement() const { return mean_displacement; }
  /**
   * Impulse the constraint has applied since the start (N s): the step's reactions
   * at its ends averaged, as the central-difference update gives the particles the
   * mean of the old and new accelerations. Its change over an interval divided by
   * the interval is the mean reaction there (the reaction of a single step chatters
   * as particles cross cells).
   */
  const Tensor<1, dim> &impulse() const { return total_impulse; }

  template <class Archive>
  void serialize(Archive &ar)
  {
    ar(total_reaction, mean_displacement, node_reaction, total_impulse);
  }

private:
  std::string set_name;
  std::string velocity_entry; ///< "Boundary conditions/Constraint N/Velocity"
  std::vector<unsigned int> node_list;
  std::array<bool, dim> component_mask{};
  std::unique_ptr<Functions::ParsedFunction<dim>> function;
  std::vector<Point<dim>> points;
  bool constant = false;
  Tensor<1, dim> constant_value;
  Tensor<1, dim> total_reaction, mean_displacement, total_impulse, previous_reaction;
  /// Reaction on each node of the set at the end of the last step (for the work).
  std::vector<Tensor<1, dim>> node_reaction;
};

/**
 * The run's constrained node sets ("Boundary conditions/Constraint N"), with unique
 * names. Imposes them on nodal rates and accelerations and tracks their reactions.
 */
template <int dim>
class NodeConstraints
{
public:
  static void declare_parameters(ParameterHandler &prm, unsigned int n_constraints);
  void parse_parameters(ParameterHandler &prm, unsigned int n_constraints,
                        const BackgroundGrid<dim> &grid);

  bool empty() const { return sets.empty(); }
  unsigned int size() const { return sets.size(); }
  const NodeConstraint<dim> &operator[](const unsigned int c) const { return *sets[c]; }
  /// Every constrained grid node (with repeats if sets overlap).
  const std::vector<unsigned int> &all_nodes() const { return nodes; }

  /// The prescribed velocities at time @p t on the displacement rates @p x.
  void impose_rates(std::vector<Tensor<1, dim>> &x, const FieldLayout &layout,
                    double t) const;
  /**
   * The prescribed accelerations at time @p t on @p x: the time derivative of the
   * prescribed velocity, by a central difference of half-width @p h (small against
   * the time over which the velocity changes; the time step is far larger).
   */
  void impose_accelerations(std::vector<Tensor<1, dim>> &x, const FieldLayout &layout,
                            double t, double h) const;

  /**
   * Distributed runs: reactions are summed over the nodes this rank owns, then over
   * the ranks.
   */
  void set_ranks(const RankReductions &r) { ranks = &r; }

  /// Updates every set's reaction and displacement; returns their work over the step.
  double update_reactions(const FieldLayout &layout, const std::vector<double> &mass,
                          const std::vector<Tensor<1, dim>> &acceleration,
                          const std::vector<Tensor<1, dim>> &force,
                          const std::vector<Tensor<1, dim>> *mass_times_acceleration,
                          const std::vector<Tensor<1, dim>> &rate, double dt);

  /// history.csv: force_<set>_x ... and displacement_<set>_x ... per set.
  void write_header(std::ostream &out) const;
  void write_row(std::ostream &out) const;

  template <class Archive>
  void serialize(Archive &ar)
  {
    for (auto &s : sets)
      s->serialize(ar);
  }

private:
  std::vector<std::unique_ptr<NodeConstraint<dim>>> sets;
  std::vector<unsigned int> nodes;
  const RankReductions *ranks = nullptr;
};
} // namespace lme_mpm

#endif
