#include <lme_mpm/base/input.h>
#include <lme_mpm/boundary/node_constraints.h>

#include <algorithm>
#include <cctype>

namespace lme_mpm
{
template <int dim>
void NodeConstraint<dim>::declare_parameters(ParameterHandler &prm)
{
  prm.declare_entry("Name", "support", Patterns::Anything(),
                    "Name of the node set; history.csv reports force_<name>_x and "
                    "displacement_<name>_x for it. Letters, digits and '_' only.");
  prm.declare_entry("Boundary ids", "", Patterns::List(Patterns::Integer(0, 5)),
                    "deal.II boundary ids of the grid faces whose nodes are in the set "
                    "(0: x-min, 1: x-max, 2: y-min, 3: y-max, 4: z-min, 5: z-max).");
  prm.declare_entry("Box", "", Patterns::Anything(),
                    "Optional box 'x0, y0[, z0], x1, y1[, z1]': grid nodes inside it "
                    "join the set.");
  prm.declare_entry("Components", "x", Patterns::MultipleSelection("x|y|z"),
                    "Velocity components that are prescribed.");
  prm.enter_subsection("Velocity");
  Functions::ParsedFunction<dim>::declare_parameters(prm, dim);
  prm.leave_subsection();
}

template <int dim>
void NodeConstraint<dim>::parse_parameters(ParameterHandler &prm,
                                           const BackgroundGrid<dim> &grid,
                                           const std::string &prefix)
{
  set_name = input::trim(prm.get("Name"));
  AssertThrow(!set_name.empty() &&
                  std::all_of(set_name.begin(), set_name.end(),
                              [](char c) { return std::isalnum(c) || c == '_'; }),
              ExcBadInput(prefix + "/Name",
                          "'" + set_name + "' must be non-empty letters, digits or '_'"));
  for (const auto &id : input::split(prm.get("Boundary ids"), ','))
  {
    const int b = std::stoi(id);
    AssertThrow(b < 2 * dim,
                ExcBadInput(prefix + "/Boundary ids", "a " + std::to_string(dim) +
                                                          "D grid has boundary ids 0.." +
                                                          std::to_string(2 * dim - 1)));
    const auto nodes = grid.nodes_on_boundary(b);
    node_list.insert(node_list.end(), nodes.begin(), nodes.end());
  }
  const auto box = input::parse_doubles(prm.get("Box"), prefix + "/Box");
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
  std::sort(node_list.begin(), node_list.end());
  node_list.erase(std::unique(node_list.begin(), node_list.end()), node_list.end());
  AssertThrow(
      !node_list.empty(),
      ExcBadInput(prefix, "the node set '" + set_name +
                              "' is empty: give boundary ids or a box holding grid "
                              "nodes"));

  const std::string comps = prm.get("Components");
  for (unsigned int d = 0; d < dim; ++d)
    component_mask[d] = comps.find("xyz"[d]) != std::string::npos;
  AssertThrow(dim == 3 || comps.find('z') == std::string::npos,
              ExcBadInput(prefix + "/Components", "'z' does not exist in 2D"));

  prm.enter_subsection("Velocity");
  function = std::make_unique<Functions::ParsedFunction<dim>>(dim);
  try
  {
    function->parse_parameters(prm);
    for (unsigned int c = 0; c < dim; ++c)
      (void)function->value(Point<dim>(), c);
  }
  catch (...)
  {
    prm.leave_subsection();
    AssertThrow(false, ExcBadInput(prefix + "/Velocity/Function expression",
                                   "not a valid expression of x, y" +
                                       std::string(dim == 3 ? ", z" : "") + ", t with " +
                                       std::to_string(dim) + " components"));
  }
  const std::string expr = prm.get("Function expression");
  prm.leave_subsection();
  for (const auto &n : node_list)
    points.push_back(grid.node_point(n));
  node_reaction.assign(node_list.size(), Tensor<1, dim>());

  // A constant expression (no x, y, z or t) is evaluated once.
  bool depends = false;
  for (const char *v : {"x", "y", "z", "t"})
    for (std::size_t pos = expr.find(v); pos != std::string::npos;
         pos             = expr.find(v, pos + 1))
    {
      const bool left_ok  = pos == 0 || !std::isalnum(expr[pos - 1]);
      const bool right_ok = pos + 1 >= expr.size() || !std::isalnum(expr[pos + 1]);
      depends             = depends || (left_ok && right_ok);
    }
  constant = !depends;
  if (constant)
  {
    constant_value.resize(1);
    for (unsigned int d = 0; d < dim; ++d)
      constant_value[0][d] = function->value(points[0], d);
  }
}

template <int dim>
Tensor<1, dim> NodeConstraint<dim>::velocity(const unsigned int i, const double t) const
{
  if (constant)
    return constant_value[0];
  function->set_time(t);
  Tensor<1, dim> v;
  for (unsigned int d = 0; d < dim; ++d)
    if (component_mask[d])
      v[d] = function->value(points[i], d);
  return v;
}

template class NodeConstraint<2>;
template class NodeConstraint<3>;
} // namespace lme_mpm
