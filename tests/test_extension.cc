// The out-of-tree extension of doc/extending.md: a user's program with its own
// softening law and material, built against the library, runs the tension bar with
// them, and the new law dissipates G_F.
#include <gtest/gtest.h>

#include "test_helpers.h"

#include <fstream>

TEST(Extension, OutOfTreePluginsBuildAndRun)
{
  const std::string src =
      std::string(LME_MPM_SOURCE_DIR) + "/doc/examples/custom_plugins";
  const std::string build = lme_mpm_test::scratch("extension_build");
  const std::string configure =
      "cmake -S " + src + " -B " + build + " -DCMAKE_BUILD_TYPE=" + LME_MPM_BUILD_TYPE +
      " -DLME_MPM_SOURCE_DIR=" + LME_MPM_SOURCE_DIR +
      " -DLME_MPM_LIBRARY=" + LME_MPM_LIBRARY + " > " + build +
      ".log 2>&1 && cmake --build " + build + " >> " + build + ".log 2>&1";
  ASSERT_EQ(std::system(configure.c_str()), 0) << "see " << build << ".log";

  const std::string out = lme_mpm_test::scratch("extension_run");
  const std::string run = build + "/my-lme-mpm " +
                          lme_mpm_test::scene("tension_bar.prm") +
                          " 'Output/Directory=" + out + "' Output/Verbosity=0" +
                          " 'Material 1/Model=bulk shear elastic'" +
                          // nu = 0, E = 30 GPa: K = E / 3, G = E / 2.
                          " 'Material 1/bulk shear elastic/Bulk modulus=10e9'" +
                          " 'Material 1/bulk shear elastic/Shear modulus=15e9'" +
                          " 'Material 1/Fracture/Softening law=power' 'Material "
                          "2/Fracture/Softening law=power'" +
                          " 'Time/End time=0.007'";
  ASSERT_EQ(std::system(run.c_str()), 0) << run;

  std::ifstream summary(out + "/summary.json");
  std::stringstream text;
  text << summary.rdbuf();
  const std::string s = text.str();
  const auto pos      = s.find("\"dissipated_energy\": ");
  ASSERT_NE(pos, std::string::npos) << s;
  const double dissipated = std::stod(s.substr(pos + 21));
  // Section 5 mm x 5 mm, G_F = 50 N/m.
  EXPECT_NEAR(dissipated / (50 * 0.005 * 0.005), 1.0, 0.05) << s;
}
