// Contact between bodies in whole runs: the sliding block, two discs.
#include <gtest/gtest.h>

#include <lme_mpm/simulation/run.h>
#include <lme_mpm/simulation/simulation.h>

#include "test_helpers.h"

#include <cmath>

using namespace lme_mpm;

namespace
{
/**
 * Sliding distance at time T of a rigid block under gravity g = 9.81 that grows
 * linearly over t_r (the scene's 0.05 s ramp): with a = g (sin theta - mu cos theta)
 * it is a (T^2/2 - T t_r/2 + t_r^2/6) for T >= t_r, the integral of the piecewise
 * linear acceleration; 0 if a <= 0.
 */
double inclined_plane(const double degrees, const double mu, const double T,
                      const double t_r = 0.05)
{
  const double theta = degrees * M_PI / 180;
  const double a     = 9.81 * (std::sin(theta) - mu * std::cos(theta));
  return std::max(0.0, a * (0.5 * T * T - 0.5 * T * t_r + t_r * t_r / 6));
}

/// The mean of column @p name over the rows with time in [t0, t1].
double mean_of(const std::string &dir, const std::string &name, const double t0,
               const double t1)
{
  const auto h   = lme_mpm_test::read_history(dir);
  const auto c   = lme_mpm_test::column(h.first, name);
  double sum     = 0;
  unsigned int n = 0;
  for (const auto &row : h.second)
    if (row[1] >= t0 && row[1] <= t1)
      sum += row[c], ++n;
  EXPECT_GT(n, 0u) << name;
  return sum / n;
}
} // namespace

TEST(Contact, BlockSlidesDownTheInclineAsCoulombPredicts)
{
  // 30 degrees, mu = 0.3: tan(theta) > mu, the block slides.
  // A history row every step: the node-by-node contact force chatters, and only its
  // mean over all steps is the force on the block.
  const auto r = lme_mpm_test::run_scene(
      "sliding_block.prm", "slide",
      {"Output/Write particle files=false", "Output/Output interval=1e-6"});
  const double exact = inclined_plane(30, 0.3, 0.5);
  std::cout << "sliding block at 30 degrees: " << r.at("sliding_distance") << " m, exact "
            << exact << " m" << std::endl;
  EXPECT_LT(std::abs(r.at("sliding_distance") - exact), 0.02 * exact);
  // The scene reports the same exact distance.
  EXPECT_NEAR(r.at("sliding_distance_exact"), exact, 1e-12 * exact);
  // The slab carries the block's weight normal to it and mu times that along it
  // (block: 0.2 m x 0.1 m x 1 m of 1000 kg/m^3).
  const std::string dir = lme_mpm_test::scratch_path("slide");
  const double weight   = 0.02 * 1000 * 9.81;
  const double normal   = mean_of(dir, "force_slab_y", 0.1, 0.5);
  const double along    = mean_of(dir, "force_slab_x", 0.1, 0.5);
  EXPECT_NEAR(normal, -weight * std::cos(M_PI / 6), 0.01 * weight);
  EXPECT_NEAR(along, 0.3 * weight * std::cos(M_PI / 6), 0.01 * weight);
}

TEST(Contact, BlockSticksBelowTheFrictionAngle)
{
  // 15 degrees: tan(theta) = 0.27 < mu = 0.3, the block stays (gravity ramped up over
  // 0.05 s: a sudden onset sets the elastic block ringing, and where the ringing
  // unloads the contact it creeps, up to 4.6 % of the frictionless distance).
  const auto r = lme_mpm_test::run_scene(
      "sliding_block.prm", "stick",
      {"Scene/sliding block/Incline angle=15", "Output/Write particle files=false"});
  const double frictionless = inclined_plane(15, 0, 0.5);
  std::cout << "sliding block at 15 degrees: " << r.at("sliding_distance")
            << " m; frictionless " << frictionless << " m" << std::endl;
  EXPECT_LT(std::abs(r.at("sliding_distance")), 0.01 * frictionless);
}

TEST(Contact, FrictionlessBlockAcceleratesFreelyAlongTheSlab)
{
  const auto r = lme_mpm_test::run_scene(
      "sliding_block.prm", "frictionless",
      {"Contact/Friction coefficient=0", "Output/Write particle files=false"});
  const double exact = inclined_plane(30, 0, 0.5);
  EXPECT_LT(std::abs(r.at("sliding_distance") - exact), 0.02 * exact);
}

namespace
{
struct DiscRun
{
  double impact_time      = -1; ///< first time the centroids' closing speed drops
  double separation_time  = -1; ///< first time after that the centroids separate
  double worst_momentum   = 0;  ///< max |total momentum| / max |one disc's momentum|
  double max_energy_drift = 0;
};

/// The two-disc collision stepped by hand, with or without multi-field contact.
DiscRun two_discs(const std::string &shape_function, const bool contact,
                  const std::vector<std::string> &extra = {})
{
  ParameterHandler prm;
  ParameterCounts counts;
  counts.bodies = 2;
  Simulation<2>::declare_parameters(prm, counts);
  prm.parse_input(lme_mpm_test::scene("two_disk_collision.prm"));
  std::vector<std::string> overrides = {
      "Output/Verbosity=0", "Output/Write particle files=false",
      "Shape functions/Type=" + shape_function,
      std::string("Contact/Type=") + (contact ? "multi-field" : "none"),
      "Time/End time=2.4",
      // At the CFL step the bounds below hold the round-off of its step count; the
      // travel limit (3.6 times the steps here) is tested on its own.
      "Time/Particle travel per step=0",
      "Output/Directory=" + lme_mpm_test::scratch("discs_" + shape_function)};
  overrides.insert(overrides.end(), extra.begin(), extra.end());
  apply_overrides(prm, overrides, false);
  std::ostringstream quiet;
  Simulation<2> sim(prm, counts, quiet);
  DiscRun out;
  const Tensor<1, 2> diagonal({M_SQRT1_2, M_SQRT1_2});
  bool approached = false;
  double scale    = 0;
  while (sim.time() < 2.4 - 0.5 * sim.time_step())
  {
    sim.step();
    const auto &p = sim.particles();
    Tensor<1, 2> momentum[2];
    double mass[2] = {0, 0};
    for (std::size_t i = 0; i < p.size(); ++i)
    {
      momentum[p.body_id[i]] += p.mass[i] * p.velocity[i];
      mass[p.body_id[i]] += p.mass[i];
    }
    // Against the largest momentum a disc has had: a disc's own passes through zero
    // as it turns, and round-off over it would read as a loss.
    scale = std::max(scale, momentum[0].norm());
    out.worst_momentum =
        std::max(out.worst_momentum, (momentum[0] + momentum[1]).norm() / scale);
    // Relative velocity of the centroids along the line of impact.
    const double closing = (momentum[0] / mass[0] - momentum[1] / mass[1]) * diagonal;
    // The discs close at 2 x 0.1 sqrt(2) m/s until they interact.
    if (!approached && closing < 0.999 * 0.2 * M_SQRT2)
    {
      approached      = true;
      out.impact_time = sim.time();
    }
    if (approached && out.separation_time < 0 && closing <= 0)
      out.separation_time = sim.time();
  }
  return out;
}
} // namespace

class DiscContact : public ::testing::TestWithParam<std::string>
{
};

TEST_P(DiscContact, DiscsBounceApartNoLaterThanOnOneFieldWithMomentumConserved)
{
  const DiscRun single = two_discs(GetParam(), false);
  const DiscRun multi  = two_discs(GetParam(), true);
  std::cout << GetParam() << ": the discs interact from t = " << multi.impact_time
            << " to " << multi.separation_time << " s with contact, from "
            << single.impact_time << " to " << single.separation_time
            << " s on one field; worst total momentum / disc momentum "
            << multi.worst_momentum << std::endl;
  ASSERT_GT(multi.separation_time, 0) << "the discs never separated";
  ASSERT_GT(single.separation_time, 0);
  // One field pulls the discs together from the moment their supports overlap, before
  // they touch (touching at 1.086 s); contact must not hold them together longer.
  EXPECT_GE(multi.impact_time, single.impact_time);
  EXPECT_LE(multi.separation_time - multi.impact_time,
            single.separation_time - single.impact_time);
  // The exchange is equal and opposite at every node: round-off only.
  EXPECT_LT(multi.worst_momentum, 1e-11);
}

INSTANTIATE_TEST_SUITE_P(Contact, DiscContact,
                         ::testing::Values("linear", "ugimp", "bspline", "lme"));

TEST(Contact, ResumedSlidingRunEndsBitwiseIdentical)
{
  const std::vector<std::string> settings = {"Time/End time=0.1", "Output/Verbosity=0",
                                             "Output/Write particle files=false",
                                             "Scene/sliding block/Incline angle=15"};
  const std::string prm                   = lme_mpm_test::scene("sliding_block.prm");
  const std::string a                     = lme_mpm_test::scratch("contact_ckpt_a"),
                    b                     = lme_mpm_test::scratch("contact_ckpt_b");
  std::ostringstream quiet;
  run_parameter_file(prm, lme_mpm_test::with_settings(settings, {}, a), quiet);
  const auto resume =
      lme_mpm_test::with_settings(settings, {"Checkpoint/Every steps=700"}, b);
  run_parameter_file(prm, resume, quiet);
  run_parameter_file(prm, resume, quiet, b);
  EXPECT_FALSE(lme_mpm_test::checksum(a).empty());
  EXPECT_EQ(lme_mpm_test::checksum(a), lme_mpm_test::checksum(b));
  EXPECT_EQ(lme_mpm_test::file_text(a + "/history.csv"),
            lme_mpm_test::file_text(b + "/history.csv"));
}

TEST(Contact, BadInputNamesTheEntry)
{
  const std::string prm = lme_mpm_test::scene("sliding_block.prm");
  const std::string dir = lme_mpm_test::scratch("contact_bad");
  const auto error      = [&](const std::vector<std::string> &o)
  { return lme_mpm_test::run_error(prm, o, dir); };
  EXPECT_NE(error({"Contact/Type=none"}).find("Contact/Type"), std::string::npos);
  EXPECT_NE(error({"Body 2/Name=block"}).find("Body 2/Name"), std::string::npos);
  EXPECT_NE(error({"Body 1/Name=a-b"}).find("Body 1/Name"), std::string::npos);
  EXPECT_NE(error({"Contact/Pair friction coefficients=1-3: 0.2"})
                .find("Contact/Pair friction coefficients"),
            std::string::npos);
  EXPECT_NE(error({"Contact/Pair friction coefficients=1-2 0.2"})
                .find("Contact/Pair friction coefficients"),
            std::string::npos);
  EXPECT_NE(error({"Body 2/Prescribed velocity/Function expression=1/0; 0"})
                .find("Body 2/Prescribed velocity"),
            std::string::npos);
  EXPECT_NE(error({"Scene/sliding block/Incline angle=90"})
                .find("Scene/sliding block/Incline angle"),
            std::string::npos);
  EXPECT_NE(
      error({"Scene/sliding block/Block=nothing"}).find("Scene/sliding block/Block"),
      std::string::npos);
  EXPECT_NE(error({"Problem/Body force=0, -9.81"}).find("Problem/Body force"),
            std::string::npos);
  EXPECT_NE(error({"Contact/Contact volume fraction=0"}).find("Contact volume fraction"),
            std::string::npos);
  // Cracks and contact combine; a crack in a body the run does not have is refused.
  const std::string crack =
      error({"Cracks/Polylines=0.5, 0.12, 0.6, 0.12", "Cracks/Body=9"});
  EXPECT_NE(crack.find("Cracks/Body"), std::string::npos) << crack;
}
