#include <deal.II/base/data_out_base.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>

#include <lme_mpm/output/grid_output.h>

namespace lme_mpm
{
namespace
{
/// The nodal mass, held in every component of a vector on the grid's (vector-valued)
/// DoFs, written as the one scalar it is.
template <int dim>
class FirstComponent : public DataPostprocessorScalar<dim>
{
public:
  FirstComponent() : DataPostprocessorScalar<dim>("nodal_mass", update_values) {}
  void evaluate_vector_field(const DataPostprocessorInputs::Vector<dim> &inputs,
                             std::vector<Vector<double>> &computed) const override
  {
    for (unsigned int q = 0; q < computed.size(); ++q)
      computed[q](0) = inputs.solution_values[q](0);
  }
};
} // namespace

template <int dim>
GridOutput<dim>::GridOutput(const std::string &directory) : files(directory, "grid")
{
}

template <int dim>
void GridOutput<dim>::write(const BackgroundGrid<dim> &grid,
                            const std::vector<double> &nodal_mass,
                            const std::vector<Tensor<1, dim>> &nodal_velocity,
                            const double time)
{
  Vector<double> velocity(grid.dof_handler().n_dofs()), mass(grid.dof_handler().n_dofs());
  for (unsigned int n = 0; n < grid.n_nodes(); ++n)
    for (unsigned int c = 0; c < dim; ++c)
    {
      velocity[grid.dof(n, c)] = nodal_velocity.empty() ? 0. : nodal_velocity[n][c];
      mass[grid.dof(n, c)]     = nodal_mass.empty() ? 0. : nodal_mass[n];
    }
  DataOut<dim> data_out;
  data_out.attach_dof_handler(grid.dof_handler());
  std::vector<DataComponentInterpretation::DataComponentInterpretation> vec(
      dim, DataComponentInterpretation::component_is_part_of_vector);
  data_out.add_data_vector(velocity, std::vector<std::string>(dim, "velocity"),
                           DataOut<dim>::type_dof_data, vec);
  const FirstComponent<dim> mass_field;
  data_out.add_data_vector(mass, mass_field);
  data_out.build_patches();
  DataOutBase::VtkFlags flags(time);
  flags.compression_level = DataOutBase::VtkFlags::best_speed;
  data_out.set_flags(flags);
  files.add(time, [&](std::ostream &out) { data_out.write_vtu(out); });
}

template class GridOutput<2>;
template class GridOutput<3>;
} // namespace lme_mpm
