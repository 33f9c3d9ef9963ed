// The drop-weight scene's input.
#include <gtest/gtest.h>

#include "test_helpers.h"

#include <cmath>
#include <map>
#include <sstream>

TEST(DropWeight, BadInputNamesTheEntry)
{
  const std::string prm = lme_mpm_test::scene("drop_weight.prm");
  const std::string dir = lme_mpm_test::scratch("drop_weight_bad");
  const auto error      = [&](const std::vector<std::string> &o)
  { return lme_mpm_test::run_error(prm, o, dir); };
  EXPECT_NE(
      error({"Scene/drop weight/Notch depth=0.1"}).find("Scene/drop weight/Notch depth"),
      std::string::npos);
  EXPECT_NE(error({"Scene/drop weight/Span=0.5"}).find("Scene/drop weight/Span"),
            std::string::npos);
  EXPECT_NE(error({"Scene/drop weight/Impact velocity=0"})
                .find("Scene/drop weight/Impact velocity"),
            std::string::npos);
  EXPECT_NE(
      error({"Scene/drop weight/Hammer mass=-1"}).find("Scene/drop weight/Hammer mass"),
      std::string::npos);
  EXPECT_NE(error({"Scene/drop weight/Supports=left"}).find("Scene/drop weight/Supports"),
            std::string::npos);
  EXPECT_NE(error({"Scene/drop weight/Hammer=striker"}).find("Scene/drop weight/Hammer"),
            std::string::npos);
  // On one velocity field the supports are node sets: bodies of their names are
  // refused, naming the entry and what it needs.
  const std::string field = error({"Contact/Type=none"});
  EXPECT_NE(field.find("Scene/drop weight/Supports"), std::string::npos) << field;
  EXPECT_NE(field.find("Contact/Type = none"), std::string::npos) << field;
  const std::string kind =
      error({"Contact/Type=none", "Scene/drop weight/Support kind=cylinders"});
  EXPECT_NE(kind.find("Scene/drop weight/Support kind"), std::string::npos) << kind;
  // The hammer's density is the scene's: a density in the file is refused, naming it.
  const std::string density = error({"Material 2/Density=7800"});
  EXPECT_NE(density.find("Material 2/Density"), std::string::npos) << density;
  EXPECT_NE(density.find("Scene/drop weight/Hammer mass"), std::string::npos) << density;
  const std::string velocity =
      error({"Body 2/Initial velocity/Function expression=0; -1"});
  EXPECT_NE(velocity.find("Scene/drop weight/Impact velocity"), std::string::npos)
      << velocity;
}

TEST(DropWeight, HeadAndGapEntriesAreChecked)
{
  const std::string prm = lme_mpm_test::scene("drop_weight.prm");
  const std::string dir = lme_mpm_test::scratch("drop_weight_head_bad");
  const auto names      = [&](const std::vector<std::string> &o, const std::string &entry)
  {
    const std::string e = lme_mpm_test::run_error(prm, o, dir);
    EXPECT_NE(e.find(entry), std::string::npos) << e;
  };
  // A head as tall as the hammer, a gap below zero.
  names({"Scene/drop weight/Head height=0.05"}, "Scene/drop weight/Head height");
  names({"Scene/drop weight/Hammer gap=-1e-4"}, "Scene/drop weight/Hammer gap");
  // A head needs both entries; its material is not the hammer body's (whose density
  // the scene sets), exists, and leaves the body some mass.
  names({"Scene/drop weight/Head material=0"}, "Scene/drop weight/Head material");
  names({"Scene/drop weight/Head height=0", "Scene/drop weight/Head material=3"},
        "Scene/drop weight/Head height");
  names({"Scene/drop weight/Head material=2"}, "Scene/drop weight/Head material");
  names({"Scene/drop weight/Head material=4"}, "Scene/drop weight/Head material");
  names({"Material 3/Density=3e7"}, "Scene/drop weight/Head material");
}

TEST(DropWeight, HeadAndBodyWeighTheHammersMass)
{
  // The head's material keeps its density, the body's gets the rest of the 120.6 kg:
  // at t = 0 only the hammer moves, so the kinetic energy is half its mass times v^2,
  // with the head and without.
  for (const std::string head : {"0.01", "0.02"})
  {
    const std::string tag = "drop_weight_mass_" + head;
    const auto r          = lme_mpm_test::run_scene("drop_weight.prm", tag,
                                                    {"Scene/drop weight/Head height=" + head,
                                                     "Scene/drop weight/Hammer gap=0.0025",
                                                     "Time/End time=2e-7"});
    const auto h          = lme_mpm_test::read_history(lme_mpm_test::scratch_path(tag));
    EXPECT_NEAR(h.second.front()[lme_mpm_test::column(h.first, "kinetic_energy")],
                0.5 * 120.6 * 2.64 * 2.64, 1e-9 * 420)
        << head;
    // The 2.5 mm gap (the hammer still on cell boundaries): no contact force yet.
    EXPECT_EQ(r.count("peak_impact_force"), 0u) << head;
  }
}

TEST(DropWeight, NeighbourhoodCheckLooksOnlyAtTheCellsTheBeamStartsIn)
{
  // The scene's graded grid has empty cells 5 mm x 1.25 mm (coarse columns crossing
  // the rows of the hammer face), where C_eps = 1.5 would not reach the next particle
  // (2.5 mm away for 1.875 mm); the beam's own cells need only C_eps >= 1.
  const std::string tag = "drop_weight_eps";
  const auto r          = lme_mpm_test::run_scene(
               "drop_weight.prm", tag,
               {"Material 1/Fracture/Epsilon factor=1.5", "Time/End time=2e-7"});
  EXPECT_EQ(r.at("particles"), 24680);
  const std::string error = lme_mpm_test::run_error(
      lme_mpm_test::scene("drop_weight.prm"), {"Material 1/Fracture/Epsilon factor=0.9"},
      lme_mpm_test::scratch("drop_weight_eps_bad"));
  EXPECT_NE(error.find("Material 1/Fracture/Epsilon factor"), std::string::npos) << error;
}
