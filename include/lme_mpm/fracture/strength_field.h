#ifndef LME_MPM_FRACTURE_STRENGTH_FIELD_H
#define LME_MPM_FRACTURE_STRENGTH_FIELD_H

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <cstdint>
#include <string>
#include <vector>

namespace lme_mpm
{
using namespace dealii;

/**
 * A random field of tensile strength over one material's particles ("Material
 * N/Fracture/Strength variability"): each particle's strength is its material's
 * 'Tensile strength' times a factor of mean 1 drawn from a Weibull or lognormal
 * distribution with a given coefficient of variation. With a correlation length l > 0
 * the factor is the distribution's quantile of a standard Gaussian random field of
 * covariance exp(-r^2 / (2 l^2)), evaluated at the particle's position at t = 0 by
 * random Fourier features (a sum of cosines with Gaussian wave vectors, Rahimi &
 * Recht 2007); with l = 0 each particle draws its own value from a hash of the seed
 * and its number. Either way a particle's factor depends only on the seed, the
 * material and the particle, not on threads, ranks or the order of the particles.
 */
template <int dim>
class StrengthField
{
public:
  enum class Distribution
  {
    none,
    weibull,
    lognormal
  };

  /// Declares the subsection "Strength variability" (call inside "Material N/Fracture").
  static void declare_parameters(ParameterHandler &prm);
  /// Reads it (inside "Material N/Fracture", named @p section in messages) for
  /// material number @p material (from 0); throws ExcBadInput naming the entry.
  void parse_parameters(ParameterHandler &prm, const std::string &section,
                        unsigned int material);

  bool active() const { return distribution != Distribution::none; }
  /// The factor of the particle numbered @p id that starts at @p x0.
  double factor(std::uint32_t id, const Point<dim> &x0) const;
  /// The standard Gaussian value behind factor().
  double gaussian(std::uint32_t id, const Point<dim> &x0) const;
  /// The distribution's cumulative distribution function of the factor.
  double cdf(double factor) const;
  /// The Weibull modulus that gives the coefficient of variation (Weibull only).
  double weibull_modulus() const { return modulus; }

private:
  Distribution distribution = Distribution::none;
  double cov = 0, correlation_length = 0, modulus = 0, scale = 1, sigma = 0;
  std::uint64_t seed = 0;
  /// Wave vectors and phases of the Fourier features.
  std::vector<Tensor<1, dim>> waves;
  std::vector<double> phases;
};
} // namespace lme_mpm

#endif
