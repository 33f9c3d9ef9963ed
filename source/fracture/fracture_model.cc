#include <lme_mpm/fracture/fracture_model.h>

namespace lme_mpm
{
void declare_shared_fracture_parameters(ParameterHandler &prm)
{
  prm.declare_entry("Epsilon factor", "2", Patterns::Double(0),
                    "C_eps: the epsilon-neighbourhood radius is C_eps times the local "
                    "grid spacing h (the shortest side of the particle's cell at t = "
                    "0); > 0, and C_eps h should exceed the particle spacing.");
  prm.declare_entry("Fracture energy", "100", Patterns::Double(0),
                    "G_c (eigenerosion) or G_F (eigensoftening), N/m, > 0.");
}

template <int dim>
void declare_fracture_parameters(ParameterHandler &prm)
{
  const auto &models = FractureModelRegistry<dim>::instance();
  prm.declare_entry("Model", "none", Patterns::Selection("none|" + models.pattern()),
                    "Fracture model of this material: none, or " +
                        models.documentation());
  models.declare_all(prm);
  declare_shared_fracture_parameters(prm);
}

template void declare_fracture_parameters<2>(ParameterHandler &);
template void declare_fracture_parameters<3>(ParameterHandler &);
} // namespace lme_mpm
