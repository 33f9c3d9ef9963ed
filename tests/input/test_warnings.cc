// What a run that goes on tells its user: summary.json's "warnings" list and one
// console line per warning.
#include <gtest/gtest.h>

#include <lme_mpm/simulation/run.h>

#include <nlohmann/json.hpp>

#include "test_helpers.h"

#include <fstream>
#include <sstream>

namespace
{
struct Warned
{
  std::vector<std::string> warnings;
  double max_fast_particle_cells = 0;
  std::size_t console_warnings   = 0;
};

Warned run_bar(const std::string &tag, std::vector<std::string> overrides)
{
  const std::string out = lme_mpm_test::scratch(tag);
  overrides.push_back("Output/Directory=" + out);
  overrides.push_back("Output/Verbosity=1");
  std::ostringstream console;
  lme_mpm::run_parameter_file(lme_mpm_test::scene("vibrating_bar.prm"), overrides,
                              console);
  nlohmann::json summary;
  std::ifstream(out + "/summary.json") >> summary;
  Warned w;
  w.warnings                = summary.at("warnings").get<std::vector<std::string>>();
  w.max_fast_particle_cells = summary.at("max_fast_particle_cells").get<double>();
  const std::string text    = console.str();
  for (auto p = text.find("warning"); p != std::string::npos;
       p      = text.find("warning", p + 1))
    ++w.console_warnings;
  return w;
}

/// The vibrating bar released at 0.1 c (its free end swings four cells), for a
/// tenth of a period.
std::vector<std::string> fast_bar(const std::string &family)
{
  return {"Shape functions/Type=" + family,
          "Body 1/Initial velocity/Function constants=v0=31.6227766, "
          "beta=1.5707963267948966",
          "Time/End time=0.0012649"};
}
} // namespace

TEST(Warnings, FastParticlesOnLinearFunctionsWarnOnceAndAreListed)
{
  const Warned w = run_bar("warn_linear", fast_bar("linear"));
  // 0.1 c over a 1 m bar on 2.5 cm cells: about four cells per wave transit.
  EXPECT_GT(w.max_fast_particle_cells, 3.5);
  EXPECT_LT(w.max_fast_particle_cells, 5.0);
  ASSERT_EQ(w.warnings.size(), 1u);
  EXPECT_NE(w.warnings[0].find("fast particles"), std::string::npos) << w.warnings[0];
  EXPECT_NE(w.warnings[0].find("bspline or lme"), std::string::npos) << w.warnings[0];
  EXPECT_EQ(w.console_warnings, 1u);
}

TEST(Warnings, SmoothFunctionsAndSlowParticlesDoNotWarn)
{
  for (const std::string family : {"bspline", "lme"})
  {
    const Warned w = run_bar("warn_" + family, fast_bar(family));
    EXPECT_GT(w.max_fast_particle_cells, 3.5) << family;
    EXPECT_TRUE(w.warnings.empty()) << family << ": " << w.warnings[0];
    EXPECT_EQ(w.console_warnings, 0u) << family;
  }
  // The shipped bar (v0 = 1e-5 m/s) on linear functions.
  const Warned slow = run_bar("warn_slow", {"Time/End time=0.0012649"});
  EXPECT_LT(slow.max_fast_particle_cells, 1e-5);
  EXPECT_TRUE(slow.warnings.empty());
}

TEST(Warnings, EntryOutsideItsPhysicalRangeIsNamedWithItsValue)
{
  // 1e14 Pa is stiffer than any solid: the run goes on and says so.
  const Warned w =
      run_bar("warn_modulus",
              {"Material 1/linear elastic/Young's modulus=1e14", "Time/End time=2e-6"});
  ASSERT_EQ(w.warnings.size(), 1u);
  EXPECT_EQ(w.warnings[0].rfind("'Material 1/linear elastic/Young's modulus' = 1e+14 Pa "
                                "(outside its physical range 1000 to 1e+13 Pa)",
                                0),
            0u)
      << w.warnings[0];
  EXPECT_EQ(w.console_warnings, 1u);
}
