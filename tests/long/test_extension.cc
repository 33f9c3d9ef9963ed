// The extension routes of doc/extending.md, through the installed package only: the
// build tree is installed into a scratch prefix, the example plug-ins installed with
// the documentation are built against it with find_package(lme_mpm), and the tension
// bar runs with the plug-ins' softening law and material, once in the stock program
// (which loads them from 'Additional shared libraries') and once in the user's own
// program. The new law must dissipate G_F.
#include <gtest/gtest.h>

#include "test_helpers.h"

#include <fstream>

namespace
{
int sh(const std::string &command)
{
  return std::system(command.c_str());
}

double dissipated_energy(const std::string &dir)
{
  const std::string s = lme_mpm_test::file_text(dir + "/summary.json");
  const auto pos      = s.find("\"dissipated_energy\": ");
  return pos == std::string::npos ? -1.0 : std::stod(s.substr(pos + 21));
}

// The plug-ins in both materials of the bar: K and G with nu = 0, E = 30 GPa
// (K = E / 3, G = E / 2), and the power law. Section 5 mm x 5 mm, G_F = 50 N/m.
const std::string plugin_settings     = "Material 1/Model = bulk shear elastic\n"
                                        "Material 1/bulk shear elastic/Bulk modulus = 10e9\n"
                                        "Material 1/bulk shear elastic/Shear modulus = 15e9\n"
                                        "Material 1/Fracture/Softening law = power\n"
                                        "Material 2/Fracture/Softening law = power\n"
                                        "Time/End time = 0.007\n"
                                        "Output/Verbosity = 0\n";
constexpr double expected_dissipation = 50 * 0.005 * 0.005;

/// "Sub/Entry = value" lines as a parameter-file fragment appended to a scene.
std::string as_prm(const std::string &lines)
{
  std::stringstream in(lines), out;
  std::string line;
  while (std::getline(in, line))
  {
    const auto eq   = line.find('=');
    const auto path = lme_mpm::input::split(line.substr(0, eq), '/');
    std::string tail =
        "set " + path.back() + " = " + lme_mpm::input::trim(line.substr(eq + 1));
    for (std::size_t i = path.size() - 1; i-- > 0;)
      tail = "subsection " + path[i] + "\n" + tail + "\nend";
    out << tail << "\n";
  }
  return out.str();
}
} // namespace

TEST(Extension, OutOfTreePluginsBuildAgainstTheInstalledPackage)
{
  const std::string root   = lme_mpm_test::scratch("installed");
  const std::string prefix = root + "/prefix", build = root + "/plugins";
  std::filesystem::create_directories(root);
  ASSERT_EQ(sh("cmake --install " LME_MPM_BINARY_DIR " --prefix " + prefix + " > " +
               root + "/install.log 2>&1"),
            0)
      << "see " << root << "/install.log";
  for (const std::string installed :
       {"/bin/lme-mpm", "/lib/cmake/lme_mpm/lme_mpmConfig.cmake",
        "/lib/cmake/lme_mpm/lme_mpmConfigVersion.cmake",
        "/include/lme_mpm/fracture/softening_law.h", "/share/lme_mpm/prm/tension_bar.prm",
        "/share/doc/lme_mpm/extending.md",
        "/share/doc/lme_mpm/examples/custom_plugins/CMakeLists.txt",
        "/share/lme_mpm/scripts/plot_brazilian.py",
        "/share/lme_mpm/scripts/plot_semicircular_bending.py",
        "/share/lme_mpm/scripts/plot_drop_weight.py",
        "/share/lme_mpm/scripts/scene_plots.py"})
    EXPECT_TRUE(std::filesystem::exists(prefix + installed)) << installed;

  // The example as installed, found through the prefix alone.
  const std::string example = prefix + "/share/doc/lme_mpm/examples/custom_plugins";
  ASSERT_EQ(sh("cmake -S " + example + " -B " + build + " -DCMAKE_PREFIX_PATH=" + prefix +
               " > " + root + "/build.log 2>&1 && cmake --build " + build +
               " --parallel 2 >> " + root + "/build.log 2>&1"),
            0)
      << "see " << root << "/build.log";
  // Nothing of the configured plug-in build points into the source or build tree.
  const std::string cache = lme_mpm_test::file_text(build + "/CMakeCache.txt");
  EXPECT_EQ(cache.find(LME_MPM_SOURCE_DIR), std::string::npos);
  EXPECT_EQ(cache.find(LME_MPM_BINARY_DIR), std::string::npos);
  EXPECT_NE(cache.find("lme_mpm_DIR:PATH=" + prefix + "/lib/cmake/lme_mpm"),
            std::string::npos);

  // The stock program, the plug-in library named in the scene file itself.
  const std::string scene = root + "/tension_bar_power.prm", stock_out = root + "/stock";
  {
    std::ofstream prm(scene);
    prm << lme_mpm_test::file_text(prefix + "/share/lme_mpm/prm/tension_bar.prm")
        << "\nset Additional shared libraries = " << build << "/libmy_plugins.so\n"
        << as_prm(plugin_settings + "Output/Directory = " + stock_out + "\n");
  }
  ASSERT_EQ(sh(prefix + "/bin/lme-mpm " + scene + " > " + root + "/stock.log 2>&1"), 0)
      << lme_mpm_test::file_text(root + "/stock.log");
  EXPECT_NEAR(dissipated_energy(stock_out) / expected_dissipation, 1.0, 0.05);
  // Without the library the same file is refused: the law's name is the plug-in's.
  ASSERT_NE(sh(prefix + "/bin/lme-mpm " + scene +
               " --set 'Additional shared libraries=' > " + root + "/refused.log 2>&1"),
            0);
  EXPECT_NE(lme_mpm_test::file_text(root + "/refused.log").find("power"),
            std::string::npos);
  // The law's own entry: another exponent still dissipates G_F; a bad one is refused
  // by its full name.
  const std::string cubic_out = root + "/cubic";
  ASSERT_EQ(sh(prefix + "/bin/lme-mpm " + scene +
               " --set 'Material 1/Fracture/power/Exponent=3' --set "
               "'Material 2/Fracture/power/Exponent=3' --set 'Output/Directory=" +
               cubic_out + "' > " + root + "/cubic.log 2>&1"),
            0)
      << lme_mpm_test::file_text(root + "/cubic.log");
  EXPECT_NEAR(dissipated_energy(cubic_out) / expected_dissipation, 1.0, 0.05);
  EXPECT_NE(dissipated_energy(cubic_out), dissipated_energy(stock_out));
  ASSERT_NE(sh(prefix + "/bin/lme-mpm " + scene +
               " --set 'Material 1/Fracture/power/Exponent=0.5' > " + root +
               "/exponent.log 2>&1"),
            0);
  EXPECT_NE(lme_mpm_test::file_text(root + "/exponent.log")
                .find("Material 1/Fracture/power/Exponent"),
            std::string::npos)
      << lme_mpm_test::file_text(root + "/exponent.log");

  // The user's own program, with the plug-ins compiled in.
  const std::string own_out = root + "/own";
  std::string own =
      build + "/my-lme-mpm " + prefix + "/share/lme_mpm/prm/tension_bar.prm";
  std::stringstream lines(plugin_settings + "Output/Directory=" + own_out + "\n");
  for (std::string line; std::getline(lines, line);)
    own += " '" + line + "'";
  ASSERT_EQ(sh(own + " > " + root + "/own.log 2>&1"), 0)
      << lme_mpm_test::file_text(root + "/own.log");
  EXPECT_NEAR(dissipated_energy(own_out) / expected_dissipation, 1.0, 0.05);
  // Both routes run the same arithmetic.
  EXPECT_EQ(dissipated_energy(own_out), dissipated_energy(stock_out));
}
