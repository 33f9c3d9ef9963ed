#ifndef LME_MPM_BOUNDARY_NODE_CONSTRAINTS_H
#define LME_MPM_BOUNDARY_NODE_CONSTRAINTS_H

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/parsed_function.h>
#include <deal.II/base/tensor.h>

#include <lme_mpm/grid/background_grid.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace lme_mpm
{
/**
 * An essential condition on a named set of grid nodes: selected velocity components
 * follow a ParsedFunction of (x, t) (0 for a fixed support, a ramp for displacement
 * control). The set comes from deal.II boundary ids of the grid and/or a box. The
 * constraint also accumulates what the output reports for the set: the reaction
 * (the force the constraint applies) and the imposed displacement.
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

  /// Prescribed velocity of node i of the set at time t.
  Tensor<1, dim> velocity(unsigned int i, double t) const;
  /// True if the velocity depends on neither time nor position (evaluated once).
  bool is_constant() const { return constant; }

  // Reported quantities, summed over the set.
  Tensor<1, dim> reaction;     ///< force the constraint applies (N)
  Tensor<1, dim> displacement; ///< mean imposed displacement (m)
  /// Reaction on each node of the set at the end of the last step (for the work).
  std::vector<Tensor<1, dim>> node_reaction;

private:
  std::string set_name;
  std::vector<unsigned int> node_list;
  std::array<bool, dim> component_mask{};
  std::unique_ptr<Functions::ParsedFunction<dim>> function;
  std::vector<Point<dim>> points;
  bool constant = false;
  std::vector<Tensor<1, dim>> constant_value;
};
} // namespace lme_mpm

#endif
