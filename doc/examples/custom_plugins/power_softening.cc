// A softening law of the user's own: sigma = f_t (1 - w / w_c)^n. Its area is
// f_t w_c / (n + 1), so w_c = (n + 1) G_F / f_t makes it dissipate G_F. Selected by
// 'Softening law = power' once this file is linked in; its exponent is the entry
// 'Material N/Fracture/power/Exponent'.
#include <lme_mpm/base/input.h>
#include <lme_mpm/fracture/softening_law.h>

#include <cmath>

namespace my_plugins
{
class PowerSoftening : public lme_mpm::SofteningLaw
{
public:
  static void declare_parameters(dealii::ParameterHandler &prm)
  {
    prm.declare_entry("Exponent", "2", dealii::Patterns::Double(),
                      "n >= 1 of sigma = f_t (1 - w/w_c)^n.");
  }

  PowerSoftening(dealii::ParameterHandler &prm, const lme_mpm::SofteningContext &c)
      : n(prm.get_double("Exponent"))
  {
    // A bad value is refused by name, like the built-in entries.
    lme_mpm::input::require_range(n, 1, 100, false, c.section + "/power/Exponent");
    w_c = (n + 1) * c.fracture_energy / c.tensile_strength;
  }
  std::string name() const override { return "power"; }
  double traction_ratio(const double w) const override
  {
    return w >= w_c ? 0.0 : std::pow(1 - w / w_c, n);
  }
  double critical_opening() const override { return w_c; }
  double max_slope() const override { return n / w_c; }

private:
  double n, w_c;
};
} // namespace my_plugins

LME_MPM_REGISTER_SOFTENING_LAW(
    my_plugins::PowerSoftening, "power",
    "sigma = f_t (1 - w/w_c)^n, w_c = (n + 1) G_F/f_t, n from 'power/Exponent' (a user "
    "plug-in).")
