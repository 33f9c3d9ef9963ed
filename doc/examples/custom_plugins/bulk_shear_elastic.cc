// A material of the user's own: isotropic elasticity given by its bulk and shear
// moduli. It reuses the library's LinearElastic for the work and only translates the
// parameters, which it declares in its own subsection 'Material N/bulk shear elastic'.
#include <lme_mpm/materials/linear_elastic.h>

namespace my_plugins
{
template <int dim>
class BulkShearElastic : public lme_mpm::materials::LinearElastic<dim>
{
public:
  static void declare_parameters(dealii::ParameterHandler &prm)
  {
    prm.declare_entry("Bulk modulus", "1e9", dealii::Patterns::Double(0), "K (Pa).");
    prm.declare_entry("Shear modulus", "1e9", dealii::Patterns::Double(0), "G (Pa).");
  }

  BulkShearElastic(dealii::ParameterHandler &prm, const lme_mpm::MaterialContext &c)
      : lme_mpm::materials::LinearElastic<dim>(
            c.density,
            youngs(prm.get_double("Bulk modulus"), prm.get_double("Shear modulus")),
            poisson(prm.get_double("Bulk modulus"), prm.get_double("Shear modulus")),
            c.plane)
  {
  }

  std::string name() const override { return "bulk shear elastic"; }

private:
  static double youngs(const double K, const double G) { return 9 * K * G / (3 * K + G); }
  static double poisson(const double K, const double G)
  {
    return (3 * K - 2 * G) / (2 * (3 * K + G));
  }
};
} // namespace my_plugins

using my_plugins::BulkShearElastic;
LME_MPM_REGISTER_MATERIAL(
    BulkShearElastic, "bulk shear elastic",
    "isotropic elasticity from bulk and shear moduli (a user plug-in).")
