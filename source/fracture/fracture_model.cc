#include <lme_mpm/base/input.h>
#include <lme_mpm/fracture/fracture_model.h>

namespace lme_mpm
{
void SharedFractureEntries::entries(EntryList &list)
{
  list.add("Epsilon factor", epsilon_factor, "2", Patterns::Double(0),
           "C_eps: the epsilon-neighbourhood radius is C_eps times the local grid "
           "spacing h (the shortest side of the particle's cell at t = 0); > 0, and "
           "C_eps h should exceed the particle spacing.");
  list.add("Fracture energy", fracture_energy, "100", Patterns::Double(0),
           "G_c (eigenerosion) or G_F (eigensoftening), N/m, > 0.");
}

SharedFractureEntries SharedFractureEntries::parse(ParameterHandler &prm,
                                                   const std::string &section)
{
  const auto in = EntryList::parse<SharedFractureEntries>(prm);
  input::require_range(in.epsilon_factor, 0, 1e6, true, section + "/Epsilon factor");
  input::require_range(in.fracture_energy, 0, 1e300, true, section + "/Fracture energy");
  return in;
}

void declare_shared_fracture_parameters(ParameterHandler &prm)
{
  EntryList::declare<SharedFractureEntries>(prm);
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
