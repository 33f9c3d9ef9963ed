#ifndef LME_MPM_FRACTURE_SOFTENING_LAW_H
#define LME_MPM_FRACTURE_SOFTENING_LAW_H

#include <lme_mpm/base/registry.h>

#include <string>

namespace lme_mpm
{
/// Parameters a cohesive law is built from.
struct SofteningContext
{
  double tensile_strength = 0; ///< f_t (Pa)
  double fracture_energy  = 0; ///< G_F (N/m)
  double critical_opening = 0; ///< w_c (m); 0: the law's own default
  std::string section;         ///< for error messages
};

/**
 * A cohesive softening law sigma(w) = f_t g(w) for the crack opening w, with g(0) = 1,
 * g decreasing to 0 at critical_opening(), and f_t * integral of g = G_F. Evaluated
 * only for particles that are softening, through a virtual call, which costs nothing
 * next to the neighbourhood sums.
 */
class SofteningLaw
{
public:
  virtual ~SofteningLaw()          = default;
  virtual std::string name() const = 0;
  /// g(w) = sigma / f_t. The opening solves ask it at more openings than they keep
  /// (bisect()), so it must depend on @p w alone. Eigensoftening's opening solve asks
  /// it only near the root (bisect_increasing()), which gives the bits of the full
  /// bisection where g is within a few ulps of its exact value.
  virtual double traction_ratio(double w) const = 0;
  /// Opening where the traction vanishes (an unbounded law stops at g = 1e-3).
  virtual double critical_opening() const = 0;
  /// max |dg/dw|, for the snap-back limit of the band width.
  virtual double max_slope() const = 0;
};

using SofteningLawRegistry = Registry<SofteningLaw, SofteningContext>;
} // namespace lme_mpm

/**
 * Registers softening law CLASS as NAME. CLASS is built from (const SofteningContext
 * &), or from (ParameterHandler &, const SofteningContext &) when it has entries of
 * its own: those it declares with a static declare_parameters(ParameterHandler &) (or
 * an Entries struct) go into the subsection 'Material N/Fracture/NAME'. CLASS may carry
 * its namespace.
 */
#define LME_MPM_REGISTER_SOFTENING_LAW(CLASS, NAME, DESCRIPTION)                         \
  LME_MPM_REGISTER_PLUGIN(::lme_mpm::SofteningLawRegistry, softening_law, CLASS, NAME,   \
                          DESCRIPTION, ::lme_mpm::PluginEntries::own_subsection)

#endif
