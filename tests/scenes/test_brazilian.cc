// The Brazilian scene's input, and material zones inside one body.
#include <gtest/gtest.h>

#include <lme_mpm/simulation/run.h>

#include "test_helpers.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

TEST(Brazilian, BadInputNamesTheEntry)
{
  const std::string prm = lme_mpm_test::scene("brazilian.prm");
  const std::string dir = lme_mpm_test::scratch("brazilian_bad");
  const auto error      = [&](const std::vector<std::string> &o)
  { return lme_mpm_test::run_error(prm, o, dir); };
  EXPECT_NE(
      error({"Scene/brazilian/Strip width=0.15"}).find("Scene/brazilian/Strip width"),
      std::string::npos);
  EXPECT_NE(error({"Scene/brazilian/Diameter=-1"}).find("Scene/brazilian/Diameter"),
            std::string::npos);
  EXPECT_NE(error({"Scene/brazilian/Loading velocity=0"})
                .find("Scene/brazilian/Loading velocity"),
            std::string::npos);
  EXPECT_NE(error({"Scene/brazilian/Stop at load fraction=1"})
                .find("Scene/brazilian/Stop at load fraction"),
            std::string::npos);
  EXPECT_NE(error({"Scene/brazilian/Centre=0.1"}).find("Scene/brazilian/Centre"),
            std::string::npos);
  EXPECT_NE(error({"Scene/brazilian/Elastic zone depth=-0.01"})
                .find("Scene/brazilian/Elastic zone depth"),
            std::string::npos);
  EXPECT_NE(error({"Body 1/Material zones=2: disc(0.1, 0.1, 0.01)"})
                .find("Body 1/Material zones"),
            std::string::npos);
  EXPECT_NE(error({"Scene/brazilian/Elastic zone material=3"})
                .find("Scene/brazilian/Elastic zone material"),
            std::string::npos);
  EXPECT_NE(error({"Scene/brazilian/Top strip=upper"}).find("Scene/brazilian/Top strip"),
            std::string::npos);
  // The scene writes the bodies' shapes: one given in the file is refused, not ignored.
  const std::string shape = error({"Body 1/Shape=disc(0.1, 0.1, 0.07)"});
  EXPECT_NE(shape.find("Body 1/Shape"), std::string::npos) << shape;
  EXPECT_NE(shape.find("Scene/brazilian/Disc"), std::string::npos) << shape;
  EXPECT_NE(error({"Body 2/Prescribed velocity/Function expression=0; -1"})
                .find("Body 2/Prescribed velocity"),
            std::string::npos);
  // The disc must fit the grid: the message names the scene's entries the user
  // changes and the grid's corners, with both extents.
  for (const auto &o :
       {"Scene/brazilian/Centre=0.05, 0.1", "Scene/brazilian/Diameter=0.25"})
  {
    const std::string m = error({o});
    EXPECT_NE(m.find("'Scene/brazilian/Diameter' and 'Scene/brazilian/Centre': the disc"),
              std::string::npos)
        << m;
    EXPECT_NE(m.find("beyond the background grid's 0 to 0.2 m: enlarge 'Grid/Lower "
                     "corner' and 'Grid/Upper corner'"),
              std::string::npos)
        << m;
  }
}

TEST(MaterialZones, AWeakZoneInsideOneBodyIsWhereTheBarBreaks)
{
  // The tension bar as one body of the stronger concrete with the weak cell as a
  // material zone: the band forms in the zone, at the zone's strength (3 MPa, not the
  // body's 3.6 MPa), and dissipates G_F over the section.
  const std::string tag = "zone_bar";
  // prm/tension_bar.prm with its two bodies replaced by the one.
  std::string text = lme_mpm_test::file_text(lme_mpm_test::scene("tension_bar.prm"));
  const auto first = text.find("# The weak cell");
  const auto after = text.find("subsection Boundary conditions");
  ASSERT_NE(first, std::string::npos);
  ASSERT_NE(after, std::string::npos);
  text = text.substr(0, first) +
         "subsection Body 1\n  set Material = 2\n  set Shape = rectangle(0, 0, 0.1, "
         "0.005)\n  set Material zones = 1: rectangle(0.05, 0, 0.0525, 0.005)\nend\n\n" +
         text.substr(after);
  const std::string prm_dir = lme_mpm_test::scratch("zone_bar_prm");
  std::filesystem::create_directories(prm_dir);
  const std::string prm = prm_dir + "/zone_bar.prm";
  std::ofstream(prm) << text;
  std::ostringstream quiet;
  const auto r = lme_mpm::run_parameter_file(
      prm,
      {"Problem/Number of bodies=1", "Output/Directory=" + lme_mpm_test::scratch(tag),
       "Output/Verbosity=0"},
      quiet);
  const std::string dir = lme_mpm_test::scratch_path(tag);
  const auto h          = lme_mpm_test::read_history(dir);
  const auto force      = lme_mpm_test::column(h.first, "force_right_x");
  double peak           = 0;
  for (const auto &row : h.second)
    peak = std::max(peak, row[force] / (0.005 * 0.005));
  std::cout << "zone bar: peak " << peak / 1e6 << " MPa, dissipated "
            << r.at("dissipated_energy") / (50 * 0.005 * 0.005) << " G_F A" << std::endl;
  EXPECT_NEAR(peak / 3e6, 1.0, 0.05);
  EXPECT_NEAR(r.at("dissipated_energy") / (50 * 0.005 * 0.005), 1.0, 0.05);
  // The band is the zone: every particle in it has softened completely, and outside
  // it damage stays below 1 % (the neighbours see the band's onset through their
  // neighbourhood mean but never reach their own strength).
  std::ifstream in(dir + "/damage.csv");
  std::string line;
  std::getline(in, line);
  // The damage column by its name (more columns follow it).
  std::size_t i_damage = 0;
  for (std::size_t at = 0, next = 0; next != std::string::npos; at = next + 1, ++i_damage)
  {
    next = line.find(',', at);
    if (line.substr(at, next == std::string::npos ? next : next - at) == "damage")
      break;
  }
  unsigned int in_zone = 0;
  while (std::getline(in, line))
  {
    const auto v      = lme_mpm::input::parse_doubles(line, "damage.csv");
    const double x0   = v[4];
    const bool inside = x0 >= 0.05 && x0 <= 0.0525;
    if (inside)
    {
      ++in_zone;
      EXPECT_EQ(v.at(i_damage), 1.0) << "x0 = " << x0;
    }
    else
      EXPECT_LT(v.at(i_damage), 0.01) << "x0 = " << x0;
  }
  EXPECT_GT(in_zone, 0u);
}

TEST(Brazilian, OpeningColumnIsTheScenesOpeningGauge)
{
  // The scene's opening is the opening gauge it adds to Output/Opening gauges: the
  // same number in both columns, the gauge in the run's recorded parameters, and a
  // user's gauge beside it.
  const std::string dir = lme_mpm_test::scratch("brazilian_gauge");
  std::ostringstream quiet;
  lme_mpm::run_parameter_file(lme_mpm_test::scene("brazilian.prm"),
                              {"Scene/brazilian/Diameter=0.1", "Grid/Cell size=0.005",
                               "Time/End time=6e-4",
                               "Output/Opening gauges=lateral: 0.06, 0.1, 0.14, 0.1",
                               "Output/Directory=" + dir, "Output/Verbosity=0"},
                              quiet);
  const auto [names, rows] = lme_mpm_test::read_history(dir);
  const std::size_t scene  = lme_mpm_test::column(names, "opening"),
                    gauge  = lme_mpm_test::column(names, "opening_diameter");
  (void)lme_mpm_test::column(names, "opening_lateral");
  ASSERT_GT(rows.size(), 5u);
  double largest = 0;
  for (const auto &row : rows)
  {
    EXPECT_EQ(row[scene], row[gauge]);
    largest = std::max(largest, std::abs(row[gauge]));
  }
  EXPECT_GT(largest, 1e-7);
  const std::string prm = lme_mpm_test::file_text(dir + "/parameters.prm");
  EXPECT_NE(prm.find("lateral: 0.06, 0.1, 0.14, 0.1; diameter: "), std::string::npos);
  // A user's gauge of the scene's name is refused, naming the list.
  const std::string e =
      lme_mpm_test::run_error(lme_mpm_test::scene("brazilian.prm"),
                              {"Scene/brazilian/Diameter=0.1", "Grid/Cell size=0.005",
                               "Output/Opening gauges=diameter: 0.06, 0.1, 0.14, 0.1"},
                              dir + "_bad");
  EXPECT_NE(e.find("two gauges are named 'diameter'"), std::string::npos) << e;
}
