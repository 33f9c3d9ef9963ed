// A softening law of the user's own: sigma = f_t (1 - w / w_c)^n. Its area is
// f_t w_c / (n + 1), so w_c = (n + 1) G_F / f_t makes it dissipate G_F. Selected by
// 'Softening law = power' once this file is linked in.
#include <lme_mpm/fracture/softening_law.h>

#include <cmath>

namespace my_plugins
{
class PowerSoftening : public lme_mpm::SofteningLaw
{
public:
  static constexpr double n = 2.0;

  explicit PowerSoftening(const lme_mpm::SofteningContext &c)
      : w_c((n + 1) * c.fracture_energy / c.tensile_strength)
  {
  }
  std::string name() const override { return "power"; }
  double traction_ratio(const double w) const override
  {
    return w >= w_c ? 0.0 : std::pow(1 - w / w_c, n);
  }
  double critical_opening() const override { return w_c; }
  double max_slope() const override { return n / w_c; }

private:
  double w_c;
};
} // namespace my_plugins

using PowerSoftening = my_plugins::PowerSoftening;
LME_MPM_REGISTER_SOFTENING_LAW(
    PowerSoftening, "power",
    "sigma = f_t (1 - w/w_c)^2, w_c = 3 G_F/f_t (a user plug-in).")
