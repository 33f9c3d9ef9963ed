#include <lme_mpm/base/format.h>
#include <lme_mpm/base/input.h>
#include <lme_mpm/base/parameters.h>
#include <lme_mpm/boundary/node_constraints.h>
#include <lme_mpm/geometry/geometry.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>

namespace lme_mpm
{
namespace
{
/// The entries of one "Constraint N", listed once for declaring and reading.
struct ConstraintEntries
{
  std::string name, boundary_ids, box, shape, components;

  void entries(EntryList &list)
  {
    list.add("Name", name, "support", Patterns::Anything(),
             "Name of the node set; history.csv reports force_<name>_x and "
             "displacement_<name>_x for it. Letters, digits and '_' only.");
    list.add("Boundary ids", boundary_ids, "", Patterns::List(Patterns::Integer(0, 5)),
             "deal.II boundary ids of the grid faces whose nodes are in the set "
             "(0: x-min, 1: x-max, 2: y-min, 3: y-max, 4: z-min, 5: z-max).");
    list.add("Box", box, "", Patterns::Anything(),
             "Optional box 'x0, y0[, z0], x1, y1[, z1]': grid nodes inside it "
             "join the set.");
    list.add("Shape", shape, "", Patterns::Anything(),
             "Optional region in the form of Body N/Shape (for example a slot at an "
             "angle): grid nodes inside it join the set.");
    list.add("Components", components, "x", Patterns::MultipleSelection("x|y|z"),
             "Velocity components that are prescribed.");
  }
};
} // namespace

template <int dim>
void NodeConstraint<dim>::declare_parameters(ParameterHandler &prm)
{
  EntryList list(prm, EntryList::Mode::declare);
  ConstraintEntries().entries(list);
  prm.enter_subsection("Velocity");
  Functions::ParsedFunction<dim>::declare_parameters(prm, dim);
  prm.leave_subsection();
}

template <int dim>
void NodeConstraint<dim>::parse_parameters(ParameterHandler &prm,
                                           const BackgroundGrid<dim> &grid,
                                           const std::string &prefix)
{
  ConstraintEntries in;
  EntryList list(prm, EntryList::Mode::parse);
  in.entries(list);
  set_name = input::trim(in.name);
  AssertThrow(!set_name.empty() &&
                  std::all_of(set_name.begin(), set_name.end(),
                              [](char c) { return std::isalnum(c) || c == '_'; }),
              ExcBadInput(prefix + "/Name",
                          "'" + set_name + "' must be non-empty letters, digits or '_'"));
  for (const auto &id : input::split(in.boundary_ids, ','))
  {
    const int b = std::stoi(id);
    AssertThrow(b < 2 * dim,
                ExcBadInput(prefix + "/Boundary ids", "a " + std::to_string(dim) +
                                                          "D grid has boundary ids 0.." +
                                                          std::to_string(2 * dim - 1)));
    const auto nodes = grid.nodes_on_boundary(b);
    node_list.insert(node_list.end(), nodes.begin(), nodes.end());
  }
  const auto box = input::parse_doubles(in.box, prefix + "/Box");
  if (!box.empty())
  {
    AssertThrow(box.size() == 2 * dim,
                ExcBadInput(prefix + "/Box", "expected " + std::to_string(2 * dim) +
                                                 " numbers (lower and upper corner)"));
    Point<dim> lo, hi;
    for (unsigned int d = 0; d < dim; ++d)
      lo[d] = box[d], hi[d] = box[dim + d];
    const auto nodes = grid.nodes_in_box(BoundingBox<dim>({lo, hi}));
    node_list.insert(node_list.end(), nodes.begin(), nodes.end());
  }
  if (!in.shape.empty())
  {
    const auto region =
        GeometryRegistry<dim>::instance().create(in.shape, prefix + "/Shape");
    for (unsigned int n = 0; n < grid.n_nodes(); ++n)
      if (region->inside(grid.node_point(n)))
        node_list.push_back(n);
  }
  std::sort(node_list.begin(), node_list.end());
  node_list.erase(std::unique(node_list.begin(), node_list.end()), node_list.end());
  AssertThrow(
      !node_list.empty(),
      ExcBadInput(prefix, "the node set '" + set_name +
                              "' is empty: give boundary ids, a box or a shape holding "
                              "grid nodes"));

  const std::string &comps = in.components;
  for (unsigned int d = 0; d < dim; ++d)
    component_mask[d] = comps.find("xyz"[d]) != std::string::npos;
  AssertThrow(dim == 3 || comps.find('z') == std::string::npos,
              ExcBadInput(prefix + "/Components", "'z' does not exist in 2D"));

  function       = std::make_unique<Functions::ParsedFunction<dim>>(dim);
  velocity_entry = prefix + "/Velocity";
  input::parse_function(prm, "Velocity", *function, velocity_entry);
  prm.enter_subsection("Velocity");
  const std::string expr = prm.get("Function expression");
  prm.leave_subsection();
  for (const auto &n : node_list)
    points.push_back(grid.node_point(n));
  node_reaction.assign(node_list.size(), Tensor<1, dim>());

  // A constant expression (no x, y, z or t) is evaluated once.
  const bool depends = input::depends_on_space_or_time(expr);
  constant           = false;
  if (!depends)
    constant_value = velocity(0, 0);
  constant = !depends;
  // Finite at every node at the start, before anything is written (and at every
  // later evaluation, by velocity()).
  if (!constant)
    for (unsigned int i = 0; i < points.size(); ++i)
      velocity(i, 0);
}

template <int dim>
Tensor<1, dim> NodeConstraint<dim>::velocity(const unsigned int i, const double t) const
{
  if (constant)
    return constant_value;
  function->set_time(t);
  Tensor<1, dim> v;
  for (unsigned int d = 0; d < dim; ++d)
    if (component_mask[d])
    {
      v[d] = function->value(points[i], d);
      if (!std::isfinite(v[d]))
      {
        std::ostringstream msg;
        msg << "component "
            << "xyz"[d] << " is " << v[d] << " at node " << point_to_string(points[i])
            << ", t = " << t << " s";
        AssertThrow(false, ExcBadInput(velocity_entry, msg.str()));
      }
    }
  return v;
}

template <int dim>
void NodeConstraint<dim>::update_reaction(
    const FieldLayout &layout, const RankReductions *ranks,
    const std::vector<double> &mass, const std::vector<Tensor<1, dim>> &acceleration,
    const std::vector<Tensor<1, dim>> &force,
    const std::vector<Tensor<1, dim>> *mass_times_acceleration,
    const std::vector<Tensor<1, dim>> &rate, const double dt, double &work)
{
  const auto reaction_at = [&](const unsigned int K, const unsigned int d)
  {
    const double ma = mass_times_acceleration ? (*mass_times_acceleration)[K][d]
                                              : mass[K] * acceleration[K][d];
    return ma - force[K][d];
  };
  previous_reaction = total_reaction;
  total_reaction    = Tensor<1, dim>();
  Tensor<1, dim> mean_rate;
  for (unsigned int i = 0; i < node_list.size(); ++i)
  {
    const unsigned int I = node_list[i];
    // Imposed rates are the same on every rank; reactions come from the rank that
    // owns the node (elsewhere its particles may be missing).
    for (unsigned int d = 0; d < dim; ++d)
      if (component_mask[d])
        mean_rate[d] += rate[I][d];
    if (ranks && !ranks->owns_node(I))
      continue;
    for (unsigned int d = 0; d < dim; ++d)
      if (component_mask[d])
      {
        // The node's other fields are constrained with it; their reactions add up.
        double r = reaction_at(I, d);
        layout.for_each_extra(I, [&](const unsigned int K) { r += reaction_at(K, d); });
        total_reaction[d] += r;
        work += 0.5 * (node_reaction[i][d] + r) * dt * rate[I][d];
        node_reaction[i][d] = r;
      }
  }
  mean_displacement += (dt / node_list.size()) * mean_rate;
}

template <int dim>
void NodeConstraint<dim>::finish_reaction(const Tensor<1, dim> &reaction, const double dt)
{
  total_reaction = reaction;
  total_impulse += (0.5 * dt) * (previous_reaction + total_reaction);
}

template <int dim>
void NodeConstraints<dim>::declare_parameters(ParameterHandler &prm,
                                              const unsigned int n_constraints)
{
  prm.enter_subsection("Boundary conditions");
  for (unsigned int c = 0; c < n_constraints; ++c)
  {
    prm.enter_subsection(input::subsection_name("Constraint", c));
    NodeConstraint<dim>::declare_parameters(prm);
    prm.leave_subsection();
  }
  prm.leave_subsection();
}

template <int dim>
void NodeConstraints<dim>::parse_parameters(ParameterHandler &prm,
                                            const unsigned int n_constraints,
                                            const BackgroundGrid<dim> &grid)
{
  sets.clear();
  nodes.clear();
  prm.enter_subsection("Boundary conditions");
  for (unsigned int c = 0; c < n_constraints; ++c)
  {
    const std::string section = input::subsection_name("Constraint", c);
    prm.enter_subsection(section);
    sets.push_back(std::make_unique<NodeConstraint<dim>>());
    sets.back()->parse_parameters(prm, grid, "Boundary conditions/" + section);
    prm.leave_subsection();
    for (unsigned int o = 0; o + 1 < sets.size(); ++o)
      AssertThrow(sets[o]->name() != sets.back()->name(),
                  ExcBadInput("Boundary conditions/" + section + "/Name",
                              "'" + sets.back()->name() + "' is used twice"));
    nodes.insert(nodes.end(), sets.back()->nodes().begin(), sets.back()->nodes().end());
  }
  prm.leave_subsection();
}

template <int dim>
void NodeConstraints<dim>::impose_rates(std::vector<Tensor<1, dim>> &x,
                                        const FieldLayout &layout, const double t) const
{
  for (const auto &c : sets)
    c->impose(
        x, layout, [&](const unsigned int i) { return c->velocity(i, t); }, 1.0);
}

template <int dim>
void NodeConstraints<dim>::impose_accelerations(std::vector<Tensor<1, dim>> &x,
                                                const FieldLayout &layout, const double t,
                                                const double h) const
{
  // The derivative at the end of the step, not the mean acceleration over it: the
  // trapezoidal corrector then carries the particle velocities at driven nodes onto
  // the prescribed ones instead of half a step behind while the velocity changes.
  for (const auto &c : sets)
    c->impose(
        x, layout,
        [&](const unsigned int i)
        { return c->velocity(i, t + h) - c->velocity(i, t - h); },
        2 * h);
}

template <int dim>
double NodeConstraints<dim>::update_reactions(
    const FieldLayout &layout, const std::vector<double> &mass,
    const std::vector<Tensor<1, dim>> &acceleration,
    const std::vector<Tensor<1, dim>> &force,
    const std::vector<Tensor<1, dim>> *mass_times_acceleration,
    const std::vector<Tensor<1, dim>> &rate, const double dt)
{
  double work = 0;
  for (auto &c : sets)
    c->update_reaction(layout, ranks, mass, acceleration, force, mass_times_acceleration,
                       rate, dt, work);
  // Each rank summed its own nodes: the totals and the work over all of them.
  std::vector<double> totals;
  for (const auto &c : sets)
    for (unsigned int d = 0; d < dim; ++d)
      totals.push_back(c->reaction()[d]);
  totals.push_back(work);
  if (ranks)
    ranks->sum(totals);
  for (unsigned int s = 0; s < sets.size(); ++s)
  {
    Tensor<1, dim> r;
    for (unsigned int d = 0; d < dim; ++d)
      r[d] = totals[s * dim + d];
    sets[s]->finish_reaction(r, dt);
  }
  return totals.back();
}

template <int dim>
void NodeConstraints<dim>::write_header(std::ostream &out) const
{
  for (const auto &c : sets)
    for (const char *q : {"force", "displacement"})
      for (unsigned int d = 0; d < dim; ++d)
        out << "," << q << "_" << c->name() << "_"
            << "xyz"[d];
}

template <int dim>
void NodeConstraints<dim>::write_row(std::ostream &out) const
{
  for (const auto &c : sets)
  {
    for (unsigned int d = 0; d < dim; ++d)
      out << "," << c->reaction()[d];
    for (unsigned int d = 0; d < dim; ++d)
      out << "," << c->displacement()[d];
  }
}

template class NodeConstraint<2>;
template class NodeConstraint<3>;
template class NodeConstraints<2>;
template class NodeConstraints<3>;
} // namespace lme_mpm
