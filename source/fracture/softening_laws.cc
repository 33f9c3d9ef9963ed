#include <lme_mpm/base/input.h>
#include <lme_mpm/fracture/softening_law.h>

#include <cmath>
#include <sstream>

namespace lme_mpm
{
namespace softening_laws
{
/// Checks a user-given w_c against the one the law implies.
void require_consistent(const SofteningContext &c, const double implied,
                        const std::string &law)
{
  if (c.critical_opening == 0)
    return;
  std::ostringstream msg;
  msg << "the " << law << " law fixes w_c = " << implied
      << " m from G_F and f_t; give 0 or that value";
  AssertThrow(std::abs(c.critical_opening - implied) <= 1e-6 * implied,
              ExcBadInput(c.section + "/Critical opening", msg.str()));
}

/// Linear softening (the paper's Fig. 1): g = 1 - w / w_c, w_c = 2 G_F / f_t.
class Linear : public SofteningLaw
{
public:
  explicit Linear(const SofteningContext &c)
      : w_c(2 * c.fracture_energy / c.tensile_strength)
  {
    require_consistent(c, w_c, "linear");
  }
  std::string name() const override { return "linear"; }
  double traction_ratio(const double w) const override
  {
    return w >= w_c ? 0.0 : 1 - w / w_c;
  }
  double critical_opening() const override { return w_c; }
  double max_slope() const override { return 1 / w_c; }

private:
  double w_c;
};

/**
 * Bilinear softening with the kink at sigma = f_t / 3 (Petersson's law): by default
 * w_c = 3.6 G_F / f_t and the kink at w = 0.8 G_F / f_t; a given w_c moves the kink so
 * that the area stays G_F (w_c must lie in (1.5, 6) G_F / f_t).
 */
class Bilinear : public SofteningLaw
{
public:
  explicit Bilinear(const SofteningContext &c)
  {
    const double l = c.fracture_energy / c.tensile_strength;
    w_c            = c.critical_opening > 0 ? c.critical_opening : 3.6 * l;
    std::ostringstream msg;
    msg << "the bilinear law needs w_c between 1.5 G_F/f_t = " << 1.5 * l
        << " m and 6 G_F/f_t = " << 6 * l << " m";
    AssertThrow(w_c > 1.5 * l && w_c < 6 * l,
                ExcBadInput(c.section + "/Critical opening", msg.str()));
    w_k = 2 * l - w_c / 3;
  }
  std::string name() const override { return "bilinear"; }
  double traction_ratio(const double w) const override
  {
    if (w <= w_k)
      return 1 - (2.0 / 3.0) * w / w_k;
    return w >= w_c ? 0.0 : (1.0 / 3.0) * (w_c - w) / (w_c - w_k);
  }
  double critical_opening() const override { return w_c; }
  double max_slope() const override
  {
    return std::max((2.0 / 3.0) / w_k, (1.0 / 3.0) / (w_c - w_k));
  }

private:
  double w_c, w_k;
};

/**
 * Exponential softening g = exp(-f_t w / G_F), area G_F. The tail is cut where
 * g = 1e-3 (w = 6.9 G_F / f_t): the particle fails there, losing 0.1 % of G_F.
 */
class Exponential : public SofteningLaw
{
public:
  explicit Exponential(const SofteningContext &c)
      : l(c.fracture_energy / c.tensile_strength)
  {
    require_consistent(c, std::log(1e3) * l, "exponential");
  }
  std::string name() const override { return "exponential"; }
  double traction_ratio(const double w) const override
  {
    return w >= critical_opening() ? 0.0 : std::exp(-w / l);
  }
  double critical_opening() const override { return std::log(1e3) * l; }
  double max_slope() const override { return 1 / l; }

private:
  double l;
};
} // namespace softening_laws
} // namespace lme_mpm

using LinearSoftening      = lme_mpm::softening_laws::Linear;
using BilinearSoftening    = lme_mpm::softening_laws::Bilinear;
using ExponentialSoftening = lme_mpm::softening_laws::Exponential;
LME_MPM_REGISTER_SOFTENING_LAW(LinearSoftening, "linear",
                               "sigma = f_t (1 - w/w_c), w_c = 2 G_F/f_t.")
LME_MPM_REGISTER_SOFTENING_LAW(BilinearSoftening, "bilinear",
                               "two lines with the kink at f_t/3 (Petersson); w_c = 3.6 "
                               "G_F/f_t unless given.")
LME_MPM_REGISTER_SOFTENING_LAW(ExponentialSoftening, "exponential",
                               "sigma = f_t exp(-f_t w/G_F), cut at 0.1 % of f_t.")
