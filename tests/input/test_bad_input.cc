// Every bad input stops the run before anything is written, with a message that names
// the offending entry (or file) and what is allowed.
#include <gtest/gtest.h>

#include <lme_mpm/base/registry.h>
#include <lme_mpm/output/run_summary.h>

#include <nlohmann/json.hpp>

#include "test_helpers.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

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
    {{"Time/End tme=1"}, "Time/End tme': no such entry (did you mean 'Time/End time'?)"},
    {{"Time/CLF=0.5"}, "(did you mean 'Time/CFL'?)"},
    {{"Output/End time=1"}, "(did you mean 'Time/End time'?)"},
    {{"Shape functions/Type=lmee"}, "(did you mean 'lme'?); a name that a plug-in"},
    {{"Body 1/Initial velocity/Function expression=q*x; 0"},
     "'q' is not a known function, variable or constant (constants are defined in "
     "'Body 1/Initial velocity/Function constants')"},
    {{"Tim/End time=1"}, "Tim/End time': no such entry"},
    {{"Time/Newmark gamma=0.3"}, "Time/Newmark gamma"},
    {{"Time/Newmark gamma=abc"}, "Time/Newmark gamma"},
    {{"Time/End time=0"}, "Time/End time"},
    {{"Time/End time=-1"}, "Time/End time"},
    {{"Time/Time step=1"}, "exceeds the stability limit"},
    {{"Time/CFL=1.5"},
     "'Time/CFL': value 1.5 is outside the allowed range (0, 1], whose upper end is "
     "'Time/Maximum CFL'"},
    {{"Time/CFL=0"}, "Time/CFL"},
    {{"Time/Maximum CFL=3"}, "Time/Maximum CFL"},
    {{"Time/Mass matrix=consistent", "Time/Mass matrix corrections=2"},
     "'Time/Mass matrix corrections': must be 0 with 'Time/Mass matrix = consistent'"},
    {{"Time/Mass matrix=consistent", "Time/Consistent mass tolerance=0.5"},
     "Time/Consistent mass tolerance"},
    {{"Time/Mass matrix=diagonal"}, "Time/Mass matrix"},
    {{"Material 1/linear elastic/Poisson's ratio=0.5"}, "Poisson's ratio"},
    {{"Material 1/linear elastic/Poisson's ratio=-1.5"}, "Poisson's ratio"},
    {{"Material 1/linear elastic/Young's modulus=0"}, "Young's modulus"},
    {{"Material 1/Density=0"}, "Material 1/Density"},
    {{"Material 1/Model=plastic"}, "Material 1/Model"},
    {{"Grid/Cell size=0.03"},
     "'Grid/Cell size': 0.03 m does not divide the extent along x (1.25 m from "
     "'Grid/Lower "
     "corner' to 'Grid/Upper corner') into a whole number of cells (41.6667); the "
     "nearest "
     "sizes that do are 0.0297619 m (42 cells) and 0.0304878 m (41 cells)"},
    {{"Grid/Cell size=0"}, "'Grid/Cell size': must be positive (got 0 m)"},
    {{"Grid/Upper corner=1, 1, 1"}, "Grid/Upper corner"},
    {{"Grid/Upper corner=-1, 0.1"}, "Grid/Upper corner"},
    {{"Grid/Step sizes x=10*0.1"}, "Grid/Step sizes x"},
    {{"Grid/Step sizes x=2.5*0.5"}, "Grid/Step sizes x"},
    {{"Body 1/Shape=rectangle(0, 0, 2, 0.1)"},
     "'Body 1/Shape': the body spans 0 to 2 m along x, beyond the background grid's 0 to "
     "1.25 m ('Grid/Lower corner' and 'Grid/Upper corner')"},
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
    // Another scene's entry would be read by nobody.
    {{"Scene/brazilian/Loading velocity=0.02"},
     "'Scene/brazilian/Loading velocity': belongs to the scene 'brazilian', but "
     "'Scene/Type' is 'none'"},
    {{"Problem/Thickness=0"}, "Problem/Thickness"},
    {{"Problem/Body force=0"}, "Problem/Body force"},
    {{"Problem/Body force ramp time=-1"}, "Problem/Body force ramp time"},
    {{"Problem/Plane assumption=axisymmetric"}, "Plane assumption"},
    {{"Problem/Number of bodies=2"},
     "'Body 2/Shape': is left at its default 'rectangle(0, 0, 1, 1)', which lies outside "
     "the grid: 'Problem/Number of bodies' asks for a 'Body 2' that the file does not "
     "describe"},
    {{"Problem/Dimension=4"}, "Problem/Dimension"},
    {{"Output/Output interval=-1"}, "Output/Output interval"},
    {{"Output/Verbosity=5"}, "Output/Verbosity"},
    {{"Verification/Exact velocity/Function expression=foo(x); 0"}, "Exact velocity"},
    {{"no equals sign"}, "expected 'Subsection/Entry=value'"},
    {{"Additional shared libraries=/nonexistent/libplugins.so"},
     "'Additional shared libraries': cannot load '/nonexistent/libplugins.so': "},
    // A file that exists but is no shared library: the loader's own reason is kept.
    {{"Additional shared libraries=" LME_MPM_SOURCE_DIR "/README.md"},
     "README.md': " LME_MPM_SOURCE_DIR "/README.md: "},
    {{"Material 1/Fracture/Model=eigenerosion",
      "Material 1/Fracture/Energy release factor=0"},
     "Energy release factor"},
    {{"Material 1/Fracture/Model=eigensoftening",
      "Material 1/Fracture/Tensile strength=0"},
     "Tensile strength"},
    {{"Material 1/Fracture/Model=eigensoftening", "Material 1/Fracture/Band width=10"},
     "'Material 1/Fracture/Band width' = 10 m is beyond the snap-back limit M / (f_t "
     "max|g'|) = 0.00222222 m (about 2 E G_F / f_t^2 for linear softening), from the "
     "P-wave modulus M = 1e+08 Pa"},
    {{"Material 1/Fracture/Model=eigenerosion", "Material 1/Fracture/Epsilon factor=0.3"},
     "smaller than the particle spacing"},
    {{"Cracks/Polylines=0, 0.5, 0.25"},
     "Cracks/Polylines': '0, 0.5, 0.25' needs an even"},
    {{"Cracks/Polylines=0, 0.5, 0.25, 0.5; 0, 0.6"}, "'0, 0.6' needs an even number"},
    {{"Cracks/Polylines=0, 0.5, 0, 0.5"}, "repeats a point"},
    {{"Cracks/Polylines=0, 0.5, 0.2, x"}, "Cracks/Polylines"},
    // Each entry in range, what they give together not: the time step, the step count,
    // the grid's memory, particle masses, functions at t = 0.
    // The wave speed made the step useless: the entries behind it are named with their
    // values, the unphysical one first.
    {{"Material 1/Density=1e-300"},
     "Invalid input for 'Material 1/Density': 'Material 1/Density' = 1e-300 kg/m^3 "
     "(outside its physical range 1 to 100000 kg/m^3), 'Material 1/linear "
     "elastic/Young's modulus' = "},
    {{"Material 1/linear elastic/Young's modulus=1e300"},
     "Invalid input for 'Material 1/linear elastic/Young's modulus': 'Material 1/linear "
     "elastic/Young's modulus' = 1e+300 Pa (outside its physical range 1000 to 1e+13 "
     "Pa), 'Material 1/Density' = "},
    {{"Grid/Cell size=1e-9"}, "Grid/Cell size': a grid of"},
    {{"Grid/Step sizes x=1e12*1e-12"}, "Grid/Step sizes x': a grid of"},
    {{"Problem/Thickness=1e-300", "Material 1/Density=1e-300",
      "Material 1/linear elastic/Young's modulus=1e-300"},
     "must be finite and positive"},
    {{"Body 1/Initial velocity/Function expression=1/(x-x); 0"},
     "Body 1/Initial velocity': is not finite at"},
    {{"Boundary conditions/Constraint 1/Velocity/Function expression=1/(t-t); 0"},
     "Constraint 1/Velocity': component x is inf"},
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
    // One quoting style: an entry is quoted once.
    EXPECT_EQ(msg.find("''"), std::string::npos) << bad.overrides[0] << ": " << msg;
    messages.insert(msg);
  }
  EXPECT_GE(bad_inputs.size(), 30u);
  // Distinct inputs give distinct messages (the entry and the value are named).
  EXPECT_GE(messages.size(), bad_inputs.size() - 2);
}

TEST(Summary, IsValidJsonWhateverItHolds)
{
  // Quotes, backslashes and line breaks in the message; values that are not finite
  // become null and are named in the message.
  lme_mpm::RunSummary s;
  s.status               = "aborted";
  s.message              = "a \"quoted\" entry, a back\\slash\nand a new line";
  s.values               = {{"fine", 1.5},
                            {"huge", std::numeric_limits<double>::infinity()},
                            {"undefined", std::numeric_limits<double>::quiet_NaN()},
                            {"steps", 12}};
  const std::string file = lme_mpm_test::scratch("summary") + ".json";
  s.write(file, "lme", 0xabcdef, 2);
  nlohmann::json j;
  ASSERT_NO_THROW(j = nlohmann::json::parse(lme_mpm_test::file_text(file)));
  EXPECT_EQ(j["status"], "aborted");
  EXPECT_EQ(j["state_checksum"], "abcdef");
  EXPECT_EQ(j["fine"], 1.5);
  EXPECT_EQ(j["steps"], 12);
  EXPECT_TRUE(j["huge"].is_null());
  EXPECT_TRUE(j["undefined"].is_null());
  const std::string message = j["message"];
  EXPECT_EQ(message.find(s.message), 0u) << message;
  EXPECT_NE(message.find("huge, undefined"), std::string::npos) << message;
}

TEST(BadInput, ParticlesBeyondTheAvailableMemoryStopBeforeAllocation)
{
  // The bar's 84 candidate cells (its box reaches into the next cell layer) at 8
  // particles per cell direction: up to 43,008 particles, about 39 MB at 900 bytes
  // each. With 10 MB available the run stops naming the entry and the amount, and
  // writes nothing.
  const std::string out = lme_mpm_test::scratch("memory");
  setenv("LME_MPM_MEMORY_LIMIT", "1e7", 1);
  const std::string msg =
      lme_mpm_test::run_error(lme_mpm_test::scene("vibrating_bar_3d.prm"),
                              {"Body 1/Particles per cell direction=8"}, out);
  unsetenv("LME_MPM_MEMORY_LIMIT");
  EXPECT_NE(msg.find("Body 1/Particles per cell direction': up to 43008 particles needs "
                     "about 0.0387 GB"),
            std::string::npos)
      << msg;
  EXPECT_FALSE(std::filesystem::exists(out));
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
  // The entry with its subsection, the line, and the declared name it is closest to.
  EXPECT_NE(msg.find("'Time/End tme': no such entry (line "), std::string::npos) << msg;
  EXPECT_NE(msg.find("(did you mean 'Time/End time'?)"), std::string::npos) << msg;
  EXPECT_FALSE(std::filesystem::exists(out));

  // A misspelled subsection and a selection that is not one of its names.
  content = text.str();
  content.replace(content.find("subsection Time"), 15, "subsection Tme");
  std::ofstream(file) << content;
  const std::string sub = lme_mpm_test::run_error(file, {}, out);
  EXPECT_NE(sub.find("'Tme': no such subsection (line "), std::string::npos) << sub;
  EXPECT_NE(sub.find("(did you mean 'Time'?)"), std::string::npos) << sub;
  content         = text.str();
  const auto type = content.find("set Type", content.find("subsection Shape functions"));
  ASSERT_NE(type, std::string::npos);
  content.replace(type, content.find('\n', type) - type, "set Type = bsplin");
  std::ofstream(file) << content;
  const std::string selection = lme_mpm_test::run_error(file, {}, out);
  EXPECT_NE(selection.find("'Shape functions/Type': 'bsplin' is not allowed (line "),
            std::string::npos)
      << selection;
  EXPECT_NE(selection.find("(did you mean 'bspline'?)"), std::string::npos) << selection;
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(BadInput, OutputDirectoryThatCannotBeMadeIsNamed)
{
  for (const auto &[directory, expected] :
       std::vector<std::pair<std::string, std::string>>{
           {LME_MPM_SOURCE_DIR "/README.md/out", "is a file, not a directory"},
           {"/proc/lme_mpm_output/run", "'Output/Directory': cannot create"}})
  {
    std::string msg;
    try
    {
      std::ostringstream quiet;
      lme_mpm::run_parameter_file(lme_mpm_test::scene("vibrating_bar.prm"),
                                  {"Output/Directory=" + directory, "Output/Verbosity=0"},
                                  quiet);
    }
    catch (const std::exception &e)
    {
      msg = lme_mpm::input::concise_message(e);
    }
    EXPECT_NE(msg.find("'Output/Directory'"), std::string::npos) << msg;
    EXPECT_NE(msg.find(expected), std::string::npos) << msg;
    EXPECT_FALSE(std::filesystem::exists(directory));
  }
}

TEST(BadInput, ExpressionErrorIsOneLine)
{
  // muParser's own report is not printed beside the message.
  const std::string log = lme_mpm_test::scratch_path("expression_error.log");
  const std::string cmd =
      std::string(LME_MPM_BINARY) + " " + lme_mpm_test::scene("vibrating_bar.prm") +
      " --set \"Body 1/Initial velocity/Function expression=q*x; 0\" --set "
      "\"Output/Directory=" +
      lme_mpm_test::scratch("expression_error") + "\" > " + log + " 2>&1";
  EXPECT_EQ(WEXITSTATUS(std::system(cmd.c_str())), 1);
  const std::string text = lme_mpm_test::file_text(log);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << text;
  EXPECT_NE(text.find("'q' is not a known function"), std::string::npos) << text;
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

TEST(RunGuards, PrescribedVelocityThatTurnsInfiniteNamesItsEntry)
{
  // Finite at t = 0, infinite later: the run stops at that step, naming the entry,
  // keeps its output and says 'aborted'.
  const std::string out = lme_mpm_test::scratch("infinite_velocity");
  const std::string msg =
      lme_mpm_test::run_error(lme_mpm_test::scene("vibrating_bar.prm"),
                              {"Boundary conditions/Constraint 1/Velocity/Function "
                               "expression=t > 1e-4 ? 1/0 : 0; 0"},
                              out);
  EXPECT_NE(msg.find("Run stopped at step"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'Boundary conditions/Constraint 1/Velocity'"), std::string::npos)
      << msg;
  ASSERT_TRUE(std::filesystem::exists(out + "/summary.json"));
  EXPECT_NE(
      lme_mpm_test::file_text(out + "/summary.json").find("\"status\": \"aborted\""),
      std::string::npos);
}

TEST(RunGuards, StepLimitEndsStoppedNotFailed)
{
  // A trial run cut short on purpose: status 'stopped' naming the limit, exit code 0.
  const std::string out = lme_mpm_test::scratch("step_limit");
  EXPECT_EQ(lme_mpm_test::run_error(lme_mpm_test::scene("vibrating_bar.prm"),
                                    {"Time/Maximum steps=5"}, out),
            "");
  const auto summary =
      nlohmann::json::parse(lme_mpm_test::file_text(out + "/summary.json"));
  EXPECT_EQ(summary["status"], "stopped");
  EXPECT_EQ(summary["stop_reason"], "Time/Maximum steps");
  EXPECT_EQ(summary["steps"], 5);
  EXPECT_NE(summary["message"].get<std::string>().find("Stopped after 5 steps"),
            std::string::npos);
  const std::string bin = LME_MPM_BINARY;
  const std::string cmd = bin + " " + lme_mpm_test::scene("vibrating_bar.prm") +
                          " --set \"Time/Maximum steps=5\" --set \"Output/Directory=" +
                          lme_mpm_test::scratch("step_limit_cli") + "\" > /dev/null 2>&1";
  EXPECT_EQ(WEXITSTATUS(std::system(cmd.c_str())), 0);
}

namespace
{
/// The vibrating bar at CFL 1.9, beyond the explicit limit, with the travel limit
/// @p travel: the run must stop with @p cause and the step, time and remedy, keep
/// history.csv (header, t = 0 and the row of the failure) and the particle files, and
/// say 'aborted' in summary.json.
void expect_blow_up_stopped(const std::string &tag, const std::string &travel,
                            const std::string &cause)
{
  const std::string out = lme_mpm_test::scratch(tag);
  const std::string msg = lme_mpm_test::run_error(
      lme_mpm_test::scene("vibrating_bar.prm"),
      {"Time/Maximum CFL=2", "Time/CFL=1.9", "Time/Mass matrix corrections=0",
       "Output/Output interval=0.0005", "Time/Particle travel per step=" + travel},
      out);
  EXPECT_NE(msg.find("Run stopped at step"), std::string::npos) << msg;
  EXPECT_NE(msg.find(cause), std::string::npos) << msg;
  EXPECT_NE(msg.find("lower the CFL number"), std::string::npos) << msg;
  ASSERT_TRUE(std::filesystem::exists(out + "/particles.pvd"));
  const std::string history = lme_mpm_test::file_text(out + "/history.csv");
  EXPECT_GE(std::count(history.begin(), history.end(), '\n'), 3);
  const std::string summary = lme_mpm_test::file_text(out + "/summary.json");
  EXPECT_NE(summary.find("\"status\": \"aborted\""), std::string::npos) << summary;
}
} // namespace

TEST(RunGuards, UnstableRunStopsWithDiagnosticAndKeepsItsOutput)
{
  // Without the travel limit, which would shorten the steps as the particles speed
  // up, a particle moves half a cell in one step: the particle guard names it.
  expect_blow_up_stopped("unstable", "0", "particle");
}

TEST(RunGuards, RunThatBlewUpStopsOnItsEnergyUnderTheTravelLimit)
{
  // With the limit on, the shortened steps would carry the wrecked bar to the end
  // time; the energy guard stops it as unstable instead.
  expect_blow_up_stopped("unstable_limited", "0.01", "the total energy has drifted by");
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

TEST(Plugins, NameClashIsRefusedNamingBothLibraries)
{
  // A plug-in library that registers a softening law called 'linear' must not replace
  // the built-in one: the run stops before writing anything, naming both owners.
  const std::string out = lme_mpm_test::scratch("clash");
  const std::string log = lme_mpm_test::scratch_path("clash.log");
  const std::string cmd = std::string(LME_MPM_BINARY) + " " +
                          lme_mpm_test::scene("vibrating_bar.prm") +
                          " --set \"Additional shared libraries=" LME_MPM_CLASH_PLUGIN
                          "\" --set \"Output/Directory=" +
                          out + "\" > " + log + " 2>&1";
  EXPECT_EQ(WEXITSTATUS(std::system(cmd.c_str())), 1);
  const std::string text = lme_mpm_test::file_text(log);
  EXPECT_NE(text.find("Additional shared libraries"), std::string::npos) << text;
  EXPECT_NE(text.find("'linear' is registered by the lme-mpm library and again by the "
                      "library '" LME_MPM_CLASH_PLUGIN "'"),
            std::string::npos)
      << text;
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(Plugins, BuiltInsRegisterEachNameOnce)
{
  EXPECT_TRUE(lme_mpm::registration_log().refused.empty());
}

TEST(BadInput, InclinedBarOutOfPlaneAngleIsThreeDimensional)
{
  // The 2D bar has one angle; a tilt out of its plane, or a 3D centre with two
  // coordinates, names the entry.
  const std::string out = lme_mpm_test::scratch("tilted_2d");
  std::string msg =
      lme_mpm_test::run_error(lme_mpm_test::scene("inclined_tension_bar.prm"),
                              {"Scene/inclined tension bar/Out-of-plane angle=10"}, out);
  EXPECT_NE(msg.find("Scene/inclined tension bar/Out-of-plane angle"), std::string::npos)
      << msg;
  msg = lme_mpm_test::run_error(lme_mpm_test::scene("inclined_tension_bar_3d.prm"),
                                {"Scene/inclined tension bar/Centre=0.04, 0.04"}, out);
  EXPECT_NE(msg.find("Scene/inclined tension bar/Centre"), std::string::npos) << msg;
  msg =
      lme_mpm_test::run_error(lme_mpm_test::scene("inclined_tension_bar_3d.prm"),
                              {"Scene/inclined tension bar/Out-of-plane angle=91"}, out);
  EXPECT_NE(msg.find("Scene/inclined tension bar/Out-of-plane angle"), std::string::npos)
      << msg;
}
