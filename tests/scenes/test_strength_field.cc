// Random tensile strength: the draws follow the chosen distribution (Kolmogorov-Smirnov
// at the 1 % level), the correlated field has the covariance it is given, and a run
// with a field gives the same state on one and two threads.
#include <deal.II/base/multithread_info.h>

#include <gtest/gtest.h>

#include <lme_mpm/fracture/strength_field.h>

#include "test_helpers.h"

#include <algorithm>
#include <cmath>

namespace
{
using namespace lme_mpm;

StrengthField<2> field(const std::string &distribution, const double cov,
                       const double length, const int seed)
{
  ParameterHandler prm;
  StrengthField<2>::declare_parameters(prm);
  prm.enter_subsection("Strength variability");
  prm.set("Distribution", distribution);
  prm.set("Coefficient of variation", cov);
  prm.set("Correlation length", length);
  prm.set("Seed", std::to_string(seed));
  prm.leave_subsection();
  StrengthField<2> f;
  f.parse_parameters(prm, "Material 1/Fracture", 0);
  return f;
}

/// The Kolmogorov-Smirnov statistic of @p sample against @p f's distribution.
double ks_statistic(std::vector<double> sample, const StrengthField<2> &f)
{
  std::sort(sample.begin(), sample.end());
  const double n = sample.size();
  double d       = 0;
  for (std::size_t i = 0; i < sample.size(); ++i)
  {
    const double F = f.cdf(sample[i]);
    d              = std::max({d, F - i / n, (i + 1) / n - F});
  }
  return d;
}

/// The 1 % critical value of the statistic for @p n independent draws.
double ks_critical(const std::size_t n)
{
  return 1.6276 / std::sqrt(double(n));
}
} // namespace

TEST(StrengthField, IndependentDrawsFollowTheirDistribution)
{
  for (const char *kind : {"lognormal", "weibull"})
    for (const double cov : {0.05, 0.2, 0.5})
    {
      const auto f = field(kind, cov, 0, 7);
      std::vector<double> s;
      for (std::uint32_t id = 0; id < 20000; ++id)
        s.push_back(f.factor(id, Point<2>(0.3, 0.1)));
      const double n = s.size();
      double mean = 0, m2 = 0, m4 = 0;
      for (const double x : s)
        mean += x / n;
      for (const double x : s)
        m2 += std::pow(x - mean, 2) / n, m4 += std::pow(x - mean, 4) / n;
      const double sd = std::sqrt(m2);
      EXPECT_LT(ks_statistic(s, f), ks_critical(s.size())) << kind << " cov " << cov;
      // Mean 1 and the coefficient of variation asked for, within four standard
      // errors; the standard deviation's error, sqrt((m4 - m2^2) / (4 n m2)), from the
      // sample's own fourth moment (the lognormal's heavy tail makes it larger than a
      // normal sample's cov / sqrt(2 n)).
      EXPECT_NEAR(mean, 1, 4 * sd / std::sqrt(n)) << kind << " cov " << cov;
      EXPECT_NEAR(sd, cov, 4 * std::sqrt((m4 - m2 * m2) / (4 * n * m2)))
          << kind << " cov " << cov;
      // Another seed, other strengths.
      const auto g = field(kind, cov, 0, 8);
      EXPECT_NE(g.factor(5, Point<2>()), f.factor(5, Point<2>()));
    }
  // The Weibull modulus of a 10 % scatter: sqrt(G(1 + 2/m) / G(1 + 1/m)^2 - 1) = 0.1
  // at m = 12.15 (G the gamma function).
  EXPECT_NEAR(field("weibull", 0.1, 0, 1).weibull_modulus(), 12.15, 0.05);
}

TEST(StrengthField, CorrelatedFieldHasItsCovarianceAndDistribution)
{
  const double l = 0.01;
  const auto f   = field("lognormal", 0.2, l, 3);
  // Points 4 l apart are independent to exp(-8): their strengths pass the test.
  std::vector<double> s;
  for (int i = 0; i < 60; ++i)
    for (int j = 0; j < 60; ++j)
      s.push_back(f.factor(0, Point<2>(4 * l * i, 4 * l * j)));
  EXPECT_LT(ks_statistic(s, f), ks_critical(s.size()));
  // Correlation of the Gaussian field at lags 0.5 l, l and 3 l over many pairs; one
  // realisation of 512 features carries a sampling error of about 0.03.
  for (const double lag : {0.5, 1.0, 3.0})
  {
    double sab = 0, saa = 0, sbb = 0;
    for (int i = 0; i < 200; ++i)
      for (int j = 0; j < 200; ++j)
      {
        const double angle = 2.399963 * (i * 200 + j); // golden-angle directions
        const Point<2> a(0.7 * l * i, 0.7 * l * j);
        const Point<2> b = a + lag * l * Tensor<1, 2>({std::cos(angle), std::sin(angle)});
        const double ga = f.gaussian(0, a), gb = f.gaussian(0, b);
        sab += ga * gb, saa += ga * ga, sbb += gb * gb;
      }
    EXPECT_NEAR(sab / std::sqrt(saa * sbb), std::exp(-0.5 * lag * lag), 0.1)
        << "lag " << lag << " l";
  }
}

TEST(StrengthField, BadInputNamesTheEntry)
{
  const std::string dir = lme_mpm_test::scratch("strength_bad");
  const auto error      = [&](const std::vector<std::string> &o)
  { return lme_mpm_test::run_error(lme_mpm_test::scene("tension_bar.prm"), o, dir); };
  const std::string section = "Material 2/Fracture/Strength variability/";
  EXPECT_NE(
      error({section + "Distribution=weibull", section + "Coefficient of variation=1.5"})
          .find("'Material 2/Fracture/Strength variability/Coefficient of variation': "
                "value 1.5 is outside the allowed range [0, 1]"),
      std::string::npos);
  EXPECT_NE(
      error({section + "Distribution=weibull", section + "Coefficient of variation=0"})
          .find("Coefficient of variation"),
      std::string::npos);
  EXPECT_NE(
      error(
          {section + "Distribution=lognormal", "Material 2/Fracture/Model=eigenerosion"})
          .find("'Material 2/Fracture/Strength variability/Distribution': varies the "
                "tensile strength of a model that has one (eigensoftening); Model = "
                "eigenerosion has none"),
      std::string::npos);
}

TEST(StrengthField, TheSameSeedGivesTheSameRunOnOneAndTwoThreads)
{
  // The tension bar's stronger material (Material 2, the bar outside its weak slice)
  // with a correlated lognormal strength: equal states on one and two threads; another
  // seed, another state.
  const std::vector<std::string> random = {
      "Material 2/Fracture/Strength variability/Distribution=lognormal",
      "Material 2/Fracture/Strength variability/Coefficient of variation=0.3",
      "Material 2/Fracture/Strength variability/Correlation length=0.005",
      "Time/End time=2e-3"};
  auto with = random;
  dealii::MultithreadInfo::set_thread_limit(1);
  lme_mpm_test::run_scene("tension_bar.prm", "strength_1", with);
  dealii::MultithreadInfo::set_thread_limit(2);
  lme_mpm_test::run_scene("tension_bar.prm", "strength_2", with);
  dealii::MultithreadInfo::set_thread_limit();
  with.push_back("Material 2/Fracture/Strength variability/Seed=2");
  lme_mpm_test::run_scene("tension_bar.prm", "strength_seed2", with);
  const std::string a = lme_mpm_test::scratch_path("strength_1"),
                    b = lme_mpm_test::scratch_path("strength_2"),
                    c = lme_mpm_test::scratch_path("strength_seed2");
  lme_mpm_test::expect_same_run(a, b);
  EXPECT_NE(lme_mpm_test::checksum(a), lme_mpm_test::checksum(c));
}
