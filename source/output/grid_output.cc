#include <deal.II/base/data_out_base.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/data_out.h>

#include <lme_mpm/output/grid_output.h>

namespace lme_mpm
{
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
  data_out.add_data_vector(mass, std::vector<std::string>(dim, "nodal_mass"),
                           DataOut<dim>::type_dof_data, vec);
  data_out.build_patches();
  DataOutBase::VtkFlags flags(time);
  flags.compression_level = DataOutBase::VtkFlags::best_speed;
  data_out.set_flags(flags);
  files.add(time, [&](std::ostream &out) { data_out.write_vtu(out); });
}

template class GridOutput<2>;
template class GridOutput<3>;
} // namespace lme_mpm
