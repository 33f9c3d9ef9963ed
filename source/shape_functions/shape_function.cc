#include <lme_mpm/shape_functions/shape_function.h>

namespace lme_mpm
{
template <int dim>
void declare_shape_function_parameters(ParameterHandler &prm)
{
  const auto &registry = ShapeFunctionRegistry<dim>::instance();
  prm.enter_subsection("Shape functions");
  prm.declare_entry("Type", "linear", Patterns::Selection(registry.pattern()),
                    "Particle-node coupling. " + registry.documentation());
  // The families' own entries sit beside the selection.
  registry.declare_all(prm);
  prm.leave_subsection();
}

template <int dim>
std::unique_ptr<ShapeFunction<dim>>
create_shape_function(ParameterHandler &prm, const ShapeFunctionContext<dim> &context)
{
  prm.enter_subsection("Shape functions");
  auto functions =
      ShapeFunctionRegistry<dim>::instance().create(prm.get("Type"), prm, context);
  prm.leave_subsection();
  return functions;
}

template void declare_shape_function_parameters<2>(ParameterHandler &);
template void declare_shape_function_parameters<3>(ParameterHandler &);
template std::unique_ptr<ShapeFunction<2>>
create_shape_function(ParameterHandler &, const ShapeFunctionContext<2> &);
template std::unique_ptr<ShapeFunction<3>>
create_shape_function(ParameterHandler &, const ShapeFunctionContext<3> &);
} // namespace lme_mpm
