#include <lme_mpm/base/input.h>
#include <lme_mpm/fracture/strength_field.h>

#include <algorithm>
#include <cmath>

namespace lme_mpm
{
namespace
{
/// SplitMix64 (Steele, Lea & Flood 2014): a 64-bit hash whose outputs pass BigCrush,
/// cheap enough to draw a particle's own value from its number.
std::uint64_t splitmix(std::uint64_t x)
{
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

/// A uniform number in (0, 1) from a hash.
double uniform(const std::uint64_t h)
{
  return (static_cast<double>(h >> 11) + 0.5) * (1.0 / 9007199254740992.0);
}

/// A standard normal number from two hashes (Box-Muller).
double normal(const std::uint64_t a, const std::uint64_t b)
{
  return std::sqrt(-2 * std::log(uniform(a))) * std::cos(2 * M_PI * uniform(b));
}

/// The coefficient of variation of a Weibull distribution of modulus m.
double weibull_cov(const double m)
{
  const double g1 = std::tgamma(1 + 1 / m), g2 = std::tgamma(1 + 2 / m);
  return std::sqrt(std::max(0.0, g2 / (g1 * g1) - 1));
}

/// Number of Fourier features: the field's one-point distribution is a sum of this
/// many cosines, Gaussian to within about 1/sqrt(2 n) in its tails.
constexpr unsigned int n_features = 512;
} // namespace

template <int dim>
void StrengthField<dim>::declare_parameters(ParameterHandler &prm)
{
  prm.enter_subsection("Strength variability");
  prm.declare_entry("Distribution", "none", Patterns::Selection("none|weibull|lognormal"),
                    "Random variation of the tensile strength over the material's "
                    "particles (eigensoftening): 'none', every particle at 'Tensile "
                    "strength'; 'weibull' or 'lognormal', each particle at 'Tensile "
                    "strength' times a factor of mean 1 and the coefficient of variation "
                    "below, drawn from that distribution (doc/theory.md, random "
                    "tensile strength).");
  prm.declare_entry("Coefficient of variation", "0.1", Patterns::Double(0),
                    "Standard deviation over mean of the strength, in (0, 1]. A "
                    "Weibull distribution takes the modulus that gives it (0.1: modulus "
                    "12.2).");
  prm.declare_entry("Correlation length", "0", Patterns::Double(0),
                    "l (m): the strengths of particles r apart correlate as "
                    "exp(-r^2 / (2 l^2)) in their Gaussian field; 0: every particle "
                    "independent (white noise, which changes with the particle "
                    "spacing: give l of a few cells to make the field independent of "
                    "the grid).");
  prm.declare_entry("Seed", "1", Patterns::Integer(0),
                    "Seed of the field: the same seed gives the same strengths on any "
                    "number of threads and ranks.");
  prm.leave_subsection();
}

template <int dim>
void StrengthField<dim>::parse_parameters(ParameterHandler &prm,
                                          const std::string &section,
                                          const unsigned int material)
{
  prm.enter_subsection("Strength variability");
  const std::string kind = prm.get("Distribution");
  cov                    = prm.get_double("Coefficient of variation");
  correlation_length     = prm.get_double("Correlation length");
  seed                   = static_cast<std::uint64_t>(prm.get_integer("Seed"));
  prm.leave_subsection();
  const std::string entry = section + "/Strength variability/";
  distribution            = kind == "weibull"     ? Distribution::weibull
                            : kind == "lognormal" ? Distribution::lognormal
                                                  : Distribution::none;
  waves.clear();
  phases.clear();
  if (!active())
    return;
  input::require_range(cov, 0, 1, false, entry + "Coefficient of variation");
  AssertThrow(cov > 0, ExcBadInput(entry + "Coefficient of variation",
                                   "must be positive with a distribution (or set "
                                   "Distribution = none)"));
  input::require_range(correlation_length, 0, 1e300, false, entry + "Correlation length");
  if (distribution == Distribution::lognormal)
    sigma = std::sqrt(std::log(1 + cov * cov));
  else
  {
    // The coefficient of variation falls as the modulus grows: bisect on log m.
    double lo = std::log(0.8), hi = std::log(1e4);
    for (int i = 0; i < 200; ++i)
    {
      const double mid                             = 0.5 * (lo + hi);
      (weibull_cov(std::exp(mid)) > cov ? lo : hi) = mid;
    }
    modulus = std::exp(0.5 * (lo + hi));
    scale   = 1 / std::tgamma(1 + 1 / modulus);
  }
  seed = splitmix(seed ^ splitmix(material + 0x51ed270b27a4f1d3ULL));
  if (correlation_length > 0)
  {
    // Wave vectors from the spectral density of the Gaussian covariance: each
    // component normal with standard deviation 1 / l; phases uniform.
    std::uint64_t state = seed;
    const auto next     = [&]() { return state = splitmix(state); };
    for (unsigned int k = 0; k < n_features; ++k)
    {
      Tensor<1, dim> w;
      for (unsigned int d = 0; d < dim; ++d)
      {
        const std::uint64_t a = next(), b = next();
        w[d] = normal(a, b) / correlation_length;
      }
      waves.push_back(w);
      phases.push_back(2 * M_PI * uniform(next()));
    }
  }
}

template <int dim>
double StrengthField<dim>::gaussian(const std::uint32_t id, const Point<dim> &x0) const
{
  if (waves.empty())
  {
    const std::uint64_t h = splitmix(seed ^ (0x2545f4914f6cdd1dULL * (id + 1ULL)));
    return normal(h, splitmix(h));
  }
  double sum = 0;
  for (unsigned int k = 0; k < waves.size(); ++k)
    sum += std::cos(waves[k] * x0 + phases[k]);
  return std::sqrt(2.0 / waves.size()) * sum;
}

template <int dim>
double StrengthField<dim>::factor(const std::uint32_t id, const Point<dim> &x0) const
{
  if (!active())
    return 1;
  const double g = gaussian(id, x0);
  if (distribution == Distribution::lognormal)
    return std::exp(sigma * g - 0.5 * sigma * sigma);
  // The Weibull quantile of the Gaussian's probability; 1 - u from erfc keeps the
  // upper tail's digits.
  const double one_minus_u = 0.5 * std::erfc(g / std::sqrt(2.0));
  return scale * std::pow(-std::log(std::max(one_minus_u, 1e-300)), 1 / modulus);
}

template <int dim>
double StrengthField<dim>::cdf(const double f) const
{
  if (f <= 0)
    return 0;
  if (distribution == Distribution::lognormal)
    return 0.5 *
           std::erfc(-(std::log(f) + 0.5 * sigma * sigma) / (sigma * std::sqrt(2.0)));
  if (distribution == Distribution::weibull)
    return 1 - std::exp(-std::pow(f / scale, modulus));
  return f >= 1 ? 1 : 0;
}

template class StrengthField<2>;
template class StrengthField<3>;
} // namespace lme_mpm
