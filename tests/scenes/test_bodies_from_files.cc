// Bodies from files: the Brazilian disc read from a Gmsh mesh and from a particle file
// holds the disc's area and splits at the built-in disc's strength; bad files are
// refused with the entry, the file and the line named.
#include <deal.II/base/quadrature_lib.h>

#include <gtest/gtest.h>

#include "test_helpers.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>

namespace
{
const std::string mesh_file =
    std::string(LME_MPM_SOURCE_DIR) + "/prm/meshes/disc_100mm.msh";

/// A 100 mm disc about (0.1, 0.1) at 5 mm cells, three particles per direction.
std::vector<std::string> small_disc(std::vector<std::string> extra)
{
  extra.insert(extra.end(), {"Scene/brazilian/Diameter=0.1", "Grid/Cell size=0.005",
                             "Body 1/Particles per cell direction=3"});
  return extra;
}

/**
 * Writes the particles of a disc of radius @p r about (0.1, 0.1) to a CSV file, at the
 * @p n-point Gauss or uniform positions of the 5 mm cells of the grid [0, 0.2]^2 (with
 * their volumes' shares) and in reverse order, with zero velocity columns; returns
 * the file's path.
 */
std::string write_disc_particles(const std::string &dir, const double r,
                                 const unsigned int n, const bool gauss)
{
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/disc.csv";
  const dealii::QGauss<1> g(n);
  const dealii::QIterated<1> u(dealii::QMidpoint<1>(), n);
  const dealii::Quadrature<1> &rule = gauss
                                          ? static_cast<const dealii::Quadrature<1> &>(g)
                                          : static_cast<const dealii::Quadrature<1> &>(u);
  std::vector<std::string> lines;
  const double h = 0.005;
  for (unsigned int i = 0; i < 40; ++i)
    for (unsigned int j = 0; j < 40; ++j)
      for (unsigned int a = 0; a < n; ++a)
        for (unsigned int b = 0; b < n; ++b)
        {
          const double x = (i + rule.point(a)[0]) * h, y = (j + rule.point(b)[0]) * h;
          if (std::hypot(x - 0.1, y - 0.1) > r)
            continue;
          std::ostringstream line;
          line << std::setprecision(17) << x << ", " << y << ", "
               << h * h * rule.weight(a) * rule.weight(b) << ", 0, 0";
          lines.push_back(line.str());
        }
  std::ofstream out(path);
  out << "# a disc of radius " << r << " m, " << n << " particles per cell direction\n"
      << "x, y, area, vx, vy\n";
  for (auto l = lines.rbegin(); l != lines.rend(); ++l)
    out << *l << "\n";
  return path;
}
} // namespace

TEST(BodiesFromFiles, GmshAndParticleFileDiscsSplitLikeTheBuiltInDisc)
{
  const double exact_area = M_PI * 0.05 * 0.05; // thickness 1 m
  const auto built_in =
      lme_mpm_test::run_scene("brazilian.prm", "disc_built_in", small_disc({}));
  const auto from_mesh = lme_mpm_test::run_scene(
      "brazilian.prm", "disc_from_mesh",
      small_disc({"Scene/brazilian/Disc shape=mesh(" + mesh_file + ", 0.001)"}));
  const std::string csv =
      write_disc_particles(lme_mpm_test::scratch("disc_particles"), 0.05, 3, true);
  const auto from_file = lme_mpm_test::run_scene(
      "brazilian.prm", "disc_from_file", small_disc({"Body 1/Particle file=" + csv}));
  const double strength = built_in.at("splitting_strength");
  ASSERT_GT(strength, 3e6);
  for (const auto *run : {&built_in, &from_mesh, &from_file})
    EXPECT_NEAR(run->at("initial_volume_disc") / exact_area, 1.0, 1e-2);
  EXPECT_NEAR(from_mesh.at("splitting_strength") / strength, 1.0, 2e-2);
  EXPECT_NEAR(from_file.at("splitting_strength") / strength, 1.0, 2e-2);
  // The file's particles are the built-in disc's, listed backwards: the same volume.
  EXPECT_NEAR(from_file.at("initial_volume_disc") / built_in.at("initial_volume_disc"),
              1.0, 1e-12);
}

TEST(BodiesFromFiles, ParticleFileOnAUniformLatticeHoldsItsArea)
{
  // Four particles per direction at the centres of equal sub-cells, given by area: the
  // run keeps every one with its volume (area times the 1 m thickness).
  const std::string csv =
      write_disc_particles(lme_mpm_test::scratch("disc_uniform"), 0.05, 4, false);
  const auto run = lme_mpm_test::run_scene(
      "brazilian.prm", "disc_uniform_run",
      small_disc({"Body 1/Particle file=" + csv, "Time/End time=2e-5"}));
  std::ifstream in(csv);
  double area = 0;
  std::string line;
  std::getline(in, line), std::getline(in, line); // the comment and the header
  while (std::getline(in, line))
    area += std::stod(line.substr(line.find(',', line.find(',') + 1) + 1));
  EXPECT_NEAR(run.at("initial_volume_disc") / area, 1.0, 1e-12);
  EXPECT_NEAR(area / (M_PI * 0.05 * 0.05), 1.0, 1e-2);
}

TEST(BodiesFromFiles, BadParticleFilesNameTheEntryFileAndLine)
{
  const std::string prm = lme_mpm_test::scene("brazilian.prm");
  const std::string dir = lme_mpm_test::scratch("bad_particle_files");
  std::filesystem::create_directories(dir);
  const auto error = [&](const std::string &content, std::vector<std::string> extra = {})
  {
    const std::string path = dir + "/p.csv";
    std::ofstream(path) << content;
    extra.push_back("Body 1/Particle file=" + path);
    return lme_mpm_test::run_error(prm, small_disc(extra), dir + "/out");
  };
  const std::string entry = "Body 1/Particle file";
  std::string e           = error("x, y\n0.1, 0.1\n");
  EXPECT_NE(e.find(entry), std::string::npos) << e;
  EXPECT_NE(e.find("one of volume or area"), std::string::npos) << e;
  e = error("x, y, volume\n0.1, 0.1, 1e-6\n0.1, 0.1\n");
  EXPECT_NE(e.find("line 3 of"), std::string::npos) << e;
  EXPECT_NE(e.find("2 values where the header names 3"), std::string::npos) << e;
  e = error("x, y, volume\n0.1, 0.1, abc\n");
  EXPECT_NE(e.find("line 2 of"), std::string::npos) << e;
  e = error("x, y, volume\n0.3, 0.1, 1e-6\n");
  EXPECT_NE(e.find("outside the background grid"), std::string::npos) << e;
  e = error("x, y, volume\n0.1, 0.1, 0\n");
  EXPECT_NE(e.find("must be positive"), std::string::npos) << e;
  e = error("x, y, volume, material\n0.1, 0.1, 1e-6, 3\n");
  EXPECT_NE(e.find("Problem/Number of materials = 2"), std::string::npos) << e;
  e = error("x, y, volume\n");
  EXPECT_NE(e.find("adds no particle"), std::string::npos) << e;
  e = error("x, y, volume\n0.1, 0.1, 1e-6\n", {"Body 1/Shape=disc(0.1, 0.1, 0.05)"});
  EXPECT_NE(e.find("Body 1/Shape"), std::string::npos) << e;
  e = lme_mpm_test::run_error(
      prm, small_disc({"Body 1/Particle file=" + dir + "/none.csv"}), dir + "/out");
  EXPECT_NE(e.find("cannot open"), std::string::npos) << e;
  e = lme_mpm_test::run_error(
      prm,
      small_disc({"Body 1/Particle file=" + dir + "/p.csv",
                  "Scene/brazilian/Disc shape=mesh(" + mesh_file + ", 0.001)"}),
      dir + "/out");
  EXPECT_NE(e.find("Scene/brazilian/Disc shape"), std::string::npos) << e;
}

TEST(BodiesFromFiles, PolygonRollerPressesLikeTheExactDisc)
{
  // The rigid roller of the indentation scene as a 96-gon inscribed in its disc (a
  // sagitta of 5 um on a 10 mm radius): the exact surfaces give the same peak force.
  std::ostringstream polygon;
  polygon << std::setprecision(17) << "polygon(";
  for (unsigned int k = 0; k < 96; ++k)
    polygon << (k ? ", " : "") << 0.03 + 0.01 * std::cos(2 * M_PI * k / 96) << ", "
            << 0.03 + 0.01 * std::sin(2 * M_PI * k / 96);
  polygon << ")";
  const auto disc   = lme_mpm_test::run_scene("rigid_indentation.prm", "roller_disc", {});
  const auto gon    = lme_mpm_test::run_scene("rigid_indentation.prm", "roller_polygon",
                                              {"Body 2/Shape=" + polygon.str()});
  const double peak = disc.at("peak_contact_force_roller");
  ASSERT_GT(peak, 0);
  EXPECT_NEAR(gon.at("peak_contact_force_roller") / peak, 1.0, 1e-2);
  EXPECT_EQ(disc.count("initial_volume_roller"), 0u); // no particles
}
