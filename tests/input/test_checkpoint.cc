// Checkpoints: a resumed run ends bitwise identical.
#include <gtest/gtest.h>

#include "test_helpers.h"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>

namespace
{
using lme_mpm_test::checksum;
using lme_mpm_test::expect_same_run;
using lme_mpm_test::file_text;
using lme_mpm_test::run_and_resume;
using lme_mpm_test::with_settings;

/// Runs @p prm with @p settings to its end in @p dir; returns the run's results.
std::map<std::string, double> run(const std::string &prm,
                                  const std::vector<std::string> &settings,
                                  const std::string &dir)
{
  std::ostringstream quiet;
  return lme_mpm::run_parameter_file(prm, with_settings(settings, {}, dir), quiet);
}

} // namespace

TEST(Checkpoint, ResumedRunEndsBitwiseIdentical)
{
  // The tension bar with eigensoftening (damage, onset data and dissipation in the
  // state) and LME (warm-start multipliers), resumed from a mid-run checkpoint.
  const std::vector<std::string> scene = {"Grid/Cell size=0.005",
                                          "Grid/Upper corner=0.1, 0.005",
                                          "Body 1/Shape=rectangle(0.05, 0, 0.055, 0.005)",
                                          "Body 2/Shape=rectangle(0, 0, 0.1, 0.005)",
                                          "Body 2/Holes=rectangle(0.05, 0, 0.055, 0.005)",
                                          "Shape functions/Type=lme",
                                          "Output/Verbosity=0",
                                          "Output/Output interval=2e-4"};
  const std::string prm                = lme_mpm_test::scene("tension_bar.prm");
  const std::string a                  = lme_mpm_test::scratch("ckpt_a"),
                    b                  = lme_mpm_test::scratch("ckpt_b");
  std::ostringstream quiet;
  auto with = [&](const std::vector<std::string> &extra, const std::string &dir)
  { return with_settings(scene, extra, dir); };
  const auto full = run(prm, scene, a);
  EXPECT_GT(full.at("dissipated_energy"), 0); // the checkpoints span the fracture
  // Continue from the last checkpoint, written some steps before the end.
  run_and_resume(prm, with_settings(scene, {"Checkpoint/Every steps=1000"}, b), b);
  EXPECT_TRUE(std::filesystem::exists(b + "/checkpoint.bin.prev"));
  expect_same_run(a, b);
  EXPECT_EQ(file_text(a + "/particles.pvd"), file_text(b + "/particles.pvd"));

  // A checkpoint of another run is refused with a clear message.
  try
  {
    lme_mpm::run_parameter_file(prm,
                                with({"Time/End time=0.004", "Grid/Cell size=0.0025",
                                      "Grid/Upper corner=0.1, 0.0025"},
                                     b),
                                quiet, b);
    ADD_FAILURE() << "resumed a mismatched checkpoint";
  }
  catch (const std::exception &e)
  {
    EXPECT_NE(lme_mpm::input::concise_message(e).find("--resume"), std::string::npos)
        << lme_mpm::input::concise_message(e);
  }

  // So is a checkpoint in another format version, and a file that is no checkpoint.
  const auto refused = [&](const std::string &bytes, const std::string &expected)
  {
    {
      std::ofstream f(b + "/checkpoint.bin", std::ios::binary);
      f << bytes;
    }
    try
    {
      lme_mpm::run_parameter_file(prm, with({}, b), quiet, b);
      ADD_FAILURE() << "resumed from '" << bytes << "'";
    }
    catch (const std::exception &e)
    {
      EXPECT_NE(lme_mpm::input::concise_message(e).find(expected), std::string::npos)
          << lme_mpm::input::concise_message(e);
    }
  };
  std::string other_version = file_text(b + "/checkpoint.bin.prev");
  ASSERT_GE(other_version.size(), 8u);
  other_version[7] = '1'; // the format before this one
  refused(other_version, "written by another version");
  refused("not a checkpoint", "is not an lme-mpm checkpoint");
}

TEST(Checkpoint, ResumeWithAChangedEntryIsRefusedNamingIt)
{
  // A changed material entry passes every size check of the checkpoint but changes
  // the results: it is refused by name. A changed output entry is not.
  const std::vector<std::string> scene = {
      "Output/Verbosity=0", "Output/Output interval=2e-4", "Time/End time=4e-4",
      "Checkpoint/Every steps=100"};
  const std::string prm = lme_mpm_test::scene("tension_bar.prm");
  const std::string dir = lme_mpm_test::scratch("ckpt_changed");
  std::ostringstream quiet;
  lme_mpm::run_parameter_file(prm, with_settings(scene, {}, dir), quiet);
  ASSERT_TRUE(std::filesystem::exists(dir + "/checkpoint.bin"));
  try
  {
    lme_mpm::run_parameter_file(
        prm, with_settings(scene, {"Material 1/Fracture/Tensile strength=3.1e6"}, dir),
        quiet, dir);
    ADD_FAILURE() << "resumed with a changed tensile strength";
  }
  catch (const std::exception &e)
  {
    const std::string msg = lme_mpm::input::concise_message(e);
    EXPECT_NE(msg.find("--resume"), std::string::npos) << msg;
    EXPECT_NE(msg.find("Material 1/Fracture/Tensile strength"), std::string::npos) << msg;
  }
  EXPECT_NO_THROW(lme_mpm::run_parameter_file(
      prm, with_settings(scene, {"Output/Write particle files=false"}, dir), quiet, dir));
}

TEST(Checkpoint, TooNarrowSlabsAreRedone)
{
  // The slab width of the fused particle-to-grid pass is the supports' reach so
  // far; a chunk reaching further does not scatter, and the transfer is redone with
  // the wider reach. A checkpoint whose stored reach (after magic, dim, ranks, size,
  // dt, steps, t and step: bytes 48 and 52, below and above) is cut by one layer in one
  // direction forces that path on the first resumed step. On the graded grid only
  // the supports of coarse cells next to the fine half reach the extra layer, so
  // the other chunks scatter before the redo, whose sums must be cleared: the result
  // must still be the uninterrupted run's, bit for bit.
  const std::vector<std::string> scene = {
      "Grid/Step sizes y=20*0.025, 40*0.0125", "Time/End time=1", "Output/Verbosity=0",
      "Output/Write particle files=false", "Output/Output interval=0.25"};
  const std::string prm = lme_mpm_test::scene("two_disk_collision.prm");
  const std::string a   = lme_mpm_test::scratch("slab_a"),
                    b   = lme_mpm_test::scratch("slab_b");
  run(prm, scene, a);
  for (const unsigned int direction : {0, 1}) // below, above
  {
    SCOPED_TRACE(direction ? "reach cut above" : "reach cut below");
    const auto cut_reach = [&](const std::string &checkpoint)
    {
      std::fstream f(checkpoint, std::ios::in | std::ios::out | std::ios::binary);
      std::uint32_t reach[2] = {0, 0};
      f.seekg(48);
      f.read(reinterpret_cast<char *>(reach), sizeof reach);
      ASSERT_GT(reach[direction], 0u);
      --reach[direction];
      f.seekp(48);
      f.write(reinterpret_cast<const char *>(reach), sizeof reach);
    };
    run_and_resume(prm, with_settings(scene, {"Checkpoint/Every steps=100"}, b), b,
                   cut_reach);
    expect_same_run(a, b);
  }
}

TEST(Checkpoint, FinishedRunExtendedToALaterEndTimeIsOneRunToThatTime)
{
  // The time step does not depend on Time/End time, and a finished run keeps a
  // checkpoint of its last step: resumed with a later end time it takes the steps,
  // and writes the rows, of one run to the later time.
  const std::vector<std::string> scene = {"Output/Verbosity=0",
                                          "Output/Output interval=1e-4",
                                          "Output/Write particle files=false"};
  const std::string prm                = lme_mpm_test::scene("tension_bar.prm");
  const std::string a                  = lme_mpm_test::scratch("extend_a"),
                    b                  = lme_mpm_test::scratch("extend_b");
  std::ostringstream quiet;
  const auto whole = lme_mpm::run_parameter_file(
      prm, with_settings(scene, {"Time/End time=1.95e-3"}, a), quiet);
  EXPECT_GT(whole.at("dissipated_energy"), 0); // the extension spans the fracture
  const auto first = lme_mpm::run_parameter_file(
      prm,
      with_settings(scene, {"Time/End time=0.77e-3", "Checkpoint/Every steps=100000"}, b),
      quiet);
  EXPECT_EQ(first.at("time_step"), whole.at("time_step"));
  ASSERT_TRUE(std::filesystem::exists(b + "/checkpoint.bin"));
  // Resuming it unchanged repeats its end; a later end time extends it.
  const auto again = lme_mpm::run_parameter_file(
      prm,
      with_settings(scene, {"Time/End time=0.77e-3", "Checkpoint/Every steps=100000"}, b),
      quiet, b);
  EXPECT_EQ(again.at("steps"), first.at("steps"));
  const auto extended = lme_mpm::run_parameter_file(
      prm,
      with_settings(scene, {"Time/End time=1.95e-3", "Checkpoint/Every steps=100000"}, b),
      quiet, b);
  EXPECT_EQ(extended.at("steps"), whole.at("steps"));
  expect_same_run(a, b);
  // An end time before the checkpoint's is refused, naming it.
  try
  {
    lme_mpm::run_parameter_file(prm, with_settings(scene, {"Time/End time=0.5e-3"}, b),
                                quiet, b);
    ADD_FAILURE() << "resumed past the end time";
  }
  catch (const std::exception &e)
  {
    EXPECT_NE(lme_mpm::input::concise_message(e).find("Time/End time"), std::string::npos)
        << lme_mpm::input::concise_message(e);
  }
}
