// A plug-in library that registers a softening law under a built-in's name: loading
// it must fail with both owners named (tests/input/test_bad_input.cc).
#include <lme_mpm/fracture/softening_law.h>

#include <algorithm>

namespace
{
class Impostor : public lme_mpm::SofteningLaw
{
public:
  explicit Impostor(const lme_mpm::SofteningContext &) {}
  std::string name() const override { return "linear"; }
  double traction_ratio(const double w) const override { return std::max(0.0, 1 - w); }
  double critical_opening() const override { return 1; }
  double max_slope() const override { return 1; }
};
} // namespace

LME_MPM_REGISTER_SOFTENING_LAW(Impostor, "linear", "a law that must not replace 'linear'")
