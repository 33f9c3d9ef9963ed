// Every bad input stops the run before anything is written, with a message that names
// the offending entry (or file) and what is allowed.
#include <gtest/gtest.h>

#include "test_helpers.h"

#include <filesystem>
#include <fstream>

namespace
{
struct BadInput
{
  std::vector<std::string> overrides;
  std::string expected; ///< a piece of the message
};

const std::vector<BadInput> bad_inputs = {
    {{"Time/End tme=1"}, "Time/End tme': no such entry"},
    {{"Tim/End time=1"}, "Tim/End time': no such entry"},
    {{"Time/Newmark gamma=0.3"}, "Time/Newmark gamma"},
    {{"Time/Newmark gamma=abc"}, "Time/Newmark gamma"},
    {{"Time/End time=0"}, "Time/End time"},
    {{"Time/End time=-1"}, "Time/End time"},
    {{"Time/Time step=1"}, "exceeds the stability limit"},
    {{"Time/CFL=1.5"}, "Time/CFL"},
    {{"Time/CFL=0"}, "Time/CFL"},
    {{"Time/Maximum CFL=3"}, "Time/Maximum CFL"},
    {{"Material 1/linear elastic/Poisson's ratio=0.5"}, "Poisson's ratio"},
    {{"Material 1/linear elastic/Poisson's ratio=-1.5"}, "Poisson's ratio"},
    {{"Material 1/linear elastic/Young's modulus=0"}, "Young's modulus"},
    {{"Material 1/Density=0"}, "Material 1/Density"},
    {{"Material 1/Model=plastic"}, "Material 1/Model"},
    {{"Grid/Cell size=0.03"}, "Grid/Cell size"},
    {{"Grid/Cell size=0"}, "Grid/Cell size"},
    {{"Grid/Upper corner=1, 1, 1"}, "Grid/Upper corner"},
    {{"Grid/Upper corner=-1, 0.1"}, "Grid/Upper corner"},
    {{"Grid/Step sizes x=10*0.1"}, "Grid/Step sizes x"},
    {{"Grid/Step sizes x=2.5*0.5"}, "Grid/Step sizes x"},
    {{"Body 1/Shape=rectangle(0, 0, 2, 0.1)"}, "reaches outside the background grid"},
    {{"Body 1/Shape=circle(0.5, 0.05, 0.01)"}, "unknown shape 'circle'"},
    {{"Body 1/Shape=disc(0.5, 0.05)"}, "'disc' takes 3 numbers"},
    {{"Body 1/Shape=disc(0.5, 0.05, -1)"}, "radius must be positive"},
    {{"Body 1/Shape=disc(0.5, 0.05, 0.0001)"}, "holds no particle"},
    {{"Body 1/Holes=slot(0, 0.05, 0.5)"}, "'slot' takes 5 numbers"},
    {{"Body 1/Material=2"}, "Body 1/Material"},
    {{"Body 1/Particles per cell direction=0"}, "Particles per cell direction"},
    {{"Body 1/Initial velocity/Function expression=sin(x"}, "Body 1/Initial velocity"},
    {{"Body 1/Initial velocity/Function expression=1"}, "Body 1/Initial velocity"},
    {{"Shape functions/Type=quadratic"}, "Shape functions/Type"},
    {{"Boundary conditions/Constraint 1/Boundary ids=7"}, "Boundary ids"},
    {{"Boundary conditions/Constraint 1/Boundary ids=4"}, "Boundary ids"},
    {{"Boundary conditions/Constraint 1/Boundary ids=",
      "Boundary conditions/Constraint 1/Box=5, 5, 6, 6"},
     "is empty"},
    {{"Boundary conditions/Constraint 1/Box=0, 0, 1"}, "Constraint 1/Box"},
    {{"Boundary conditions/Constraint 2/Name=fixed_end"}, "is used twice"},
    {{"Boundary conditions/Constraint 1/Name=bad name"}, "Constraint 1/Name"},
    {{"Boundary conditions/Constraint 1/Components=w"}, "Components"},
    {{"Boundary conditions/Constraint 1/Components=z"}, "'z' does not exist in 2D"},
    {{"Boundary conditions/Constraint 1/Velocity/Function expression=0"}, "Velocity"},
    {{"Problem/Thickness=0"}, "Problem/Thickness"},
    {{"Problem/Body force=0"}, "Problem/Body force"},
    {{"Problem/Plane assumption=axisymmetric"}, "Plane assumption"},
    {{"Problem/Number of bodies=2"}, "Body 2/Shape"},
    {{"Problem/Dimension=4"}, "Problem/Dimension"},
    {{"Output/Output interval=-1"}, "Output/Output interval"},
    {{"Output/Verbosity=5"}, "Output/Verbosity"},
    {{"Verification/Exact velocity/Function expression=foo(x); 0"}, "Exact velocity"},
    {{"no equals sign"}, "expected 'Subsection/Entry=value'"},
    {{"Material 1/Fracture/Model=eigenerosion",
      "Material 1/Fracture/Energy release factor=0"},
     "Energy release factor"},
    {{"Material 1/Fracture/Model=eigensoftening",
      "Material 1/Fracture/Tensile strength=0"},
     "Tensile strength"},
    {{"Material 1/Fracture/Model=eigenerosion", "Material 1/Fracture/Epsilon factor=0.3"},
     "smaller than the particle spacing"},
    {{"Cracks/Polylines=0, 0.5, 0.25"},
     "Cracks/Polylines': '0, 0.5, 0.25' needs an even"},
    {{"Cracks/Polylines=0, 0.5, 0.25, 0.5; 0, 0.6"}, "'0, 0.6' needs an even number"},
    {{"Cracks/Polylines=0, 0.5, 0, 0.5"}, "repeats a point"},
    {{"Cracks/Polylines=0, 0.5, 0.2, x"}, "Cracks/Polylines"},
};
} // namespace

TEST(BadInput, EachCaseFailsWithItsOwnMessageAndWritesNothing)
{
  const std::string prm = lme_mpm_test::scene("vibrating_bar.prm");
  std::set<std::string> messages;
  for (const auto &bad : bad_inputs)
  {
    const std::string out = lme_mpm_test::scratch("bad_input");
    const std::string msg = lme_mpm_test::run_error(prm, bad.overrides, out);
    EXPECT_NE(msg.find(bad.expected), std::string::npos)
        << "override '" << bad.overrides[0] << "' gave: '" << msg << "'";
    EXPECT_FALSE(std::filesystem::exists(out)) << bad.overrides[0] << " wrote output";
    messages.insert(msg);
  }
  EXPECT_GE(bad_inputs.size(), 30u);
  // Distinct inputs give distinct messages (the entry and the value are named).
  EXPECT_GE(messages.size(), bad_inputs.size() - 2);
}

TEST(BadInput, MissingFileAndMisspelledEntryInFile)
{
  const std::string out = lme_mpm_test::scratch("bad_file");
  EXPECT_NE(
      lme_mpm_test::run_error("/nonexistent/scene.prm", {}, out).find("does not exist"),
      std::string::npos);

  const std::string file = lme_mpm_test::scratch("bad_file_prm") + ".prm";
  std::ifstream in(lme_mpm_test::scene("vibrating_bar.prm"));
  std::stringstream text;
  text << in.rdbuf();
  std::string content = text.str();
  content.replace(content.find("set End time"), 12, "set End tme");
  std::ofstream(file) << content;
  const std::string msg = lme_mpm_test::run_error(file, {}, out);
  EXPECT_NE(msg.find("End tme"), std::string::npos) << msg;
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(BadInput, CommandLineExitCodes)
{
  const std::string bin = LME_MPM_BINARY;
  const std::string out = lme_mpm_test::scratch("cli");
  auto run              = [&](const std::string &args)
  { return WEXITSTATUS(std::system((bin + " " + args + " > /dev/null 2>&1").c_str())); };
  EXPECT_EQ(run("--help"), 0);
  EXPECT_EQ(run(""), 2);
  EXPECT_EQ(run("--bogus-flag x.prm"), 2);
  EXPECT_EQ(run(lme_mpm_test::scene("vibrating_bar.prm") +
                " --set \"Time/CFL=7\" --set " + "\"Output/Directory=" + out + "\""),
            1);
  EXPECT_FALSE(std::filesystem::exists(out));
  EXPECT_EQ(run("--print-parameters"), 0);
}

TEST(RunGuards, UnstableRunStopsWithDiagnosticAndKeepsItsOutput)
{
  // CFL 1.9 is beyond the explicit limit: the bar blows up. The run must stop with the
  // step, time, particle and cause, keep history.csv and the particle files, and say
  // 'aborted' in summary.json.
  const std::string out = lme_mpm_test::scratch("unstable");
  const std::string msg = lme_mpm_test::run_error(
      lme_mpm_test::scene("vibrating_bar.prm"),
      {"Time/Maximum CFL=2", "Time/CFL=1.9", "Time/Mass matrix corrections=0",
       "Output/Output interval=0.0005"},
      out);
  EXPECT_NE(msg.find("Run stopped at step"), std::string::npos) << msg;
  EXPECT_NE(msg.find("particle"), std::string::npos) << msg;
  EXPECT_NE(msg.find("lower the CFL number"), std::string::npos) << msg;
  ASSERT_TRUE(std::filesystem::exists(out + "/history.csv"));
  ASSERT_TRUE(std::filesystem::exists(out + "/particles.pvd"));
  std::ifstream history(out + "/history.csv");
  std::string line;
  unsigned int rows = 0;
  while (std::getline(history, line))
    ++rows;
  EXPECT_GE(rows, 3u); // header, t = 0, and the row written at the failure
  std::ifstream summary(out + "/summary.json");
  std::stringstream text;
  text << summary.rdbuf();
  EXPECT_NE(text.str().find("\"status\": \"aborted\""), std::string::npos) << text.str();
}

TEST(Documentation, ParametersPageIsCurrent)
{
  // doc/parameters.md holds the --print-parameters output between ``` fences.
  const std::string out = lme_mpm_test::scratch("params") + ".txt";
  ASSERT_EQ(
      std::system((std::string(LME_MPM_BINARY) + " --print-parameters > " + out).c_str()),
      0);
  std::ifstream printed(out),
      page(std::string(LME_MPM_SOURCE_DIR) + "/doc/parameters.md");
  std::stringstream a, b;
  a << printed.rdbuf();
  b << page.rdbuf();
  const std::string text = b.str();
  const auto open        = text.find("```\n");
  const auto close       = text.rfind("```");
  ASSERT_NE(open, std::string::npos);
  EXPECT_EQ(text.substr(open + 4, close - open - 4), a.str())
      << "doc/parameters.md is stale: run scripts/update_parameters_doc.sh build";
}
