// Output of whole runs: the particle and grid series, probes.
#include <deal.II/base/multithread_info.h>

#include <gtest/gtest.h>

#include <lme_mpm/grid/background_grid.h>
#include <lme_mpm/output/particle_output.h>
#include <lme_mpm/output/probes.h>
#include <lme_mpm/output/run_files.h>
#include <lme_mpm/particles/damage_form.h>
#include <lme_mpm/particles/particle_store.h>

#include "test_helpers.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

using namespace lme_mpm;

TEST(Output, ParticleAndGridSeriesListEveryFileWritten)
{
  lme_mpm_test::run_scene("tension_bar.prm", "series",
                          {"Output/Write grid files=true",
                           "Output/Write particle files=true", "Time/End time=2e-5"});
  const std::string dir = lme_mpm_test::scratch_path("series");
  // The files a PVD record lists, each checked to exist.
  const auto listed = [&](const std::string &stem)
  {
    const std::string pvd = lme_mpm_test::file_text(dir + "/" + stem + ".pvd");
    unsigned int n        = 0;
    for (auto pos = pvd.find("file=\""); pos != std::string::npos;
         pos      = pvd.find("file=\"", pos + 1), ++n)
    {
      const auto begin = pos + 6, end = pvd.find('"', begin);
      EXPECT_TRUE(std::filesystem::exists(dir + "/" + pvd.substr(begin, end - begin)))
          << pvd.substr(begin, end - begin);
    }
    return n;
  };
  const unsigned int particle_files = listed("particles");
  EXPECT_GE(particle_files, 3u); // t = 0, 1e-5, 2e-5
  EXPECT_EQ(listed("grid"), particle_files);
  EXPECT_TRUE(std::filesystem::exists(dir + "/grid_00000.vtu"));
}

TEST(Output, ProbesReportTheEffectiveStress)
{
  // Three particles of equal volume and equal undamaged stress under one probe: intact,
  // half damaged and failed. The probe averages what the forces use: (1 + 0.5 + 0) / 3.
  ParameterHandler prm;
  Probes<2>::declare_parameters(prm, 1);
  prm.enter_subsection("Output");
  prm.enter_subsection("Probe 1");
  prm.set("Name", "p");
  prm.set("Point", "0, 0");
  prm.set("Radius", "1");
  prm.leave_subsection();
  prm.leave_subsection();
  Probes<2> probes;
  probes.parse_parameters(prm, 1);
  ParticleStore<2> store;
  for (unsigned int p = 0; p < 3; ++p)
  {
    store.add(Point<2>(0.1 * p, 0), 1.0, 2.0, 0, 0);
    store.stress[p][0][0] = 6e6;
    store.stress[p][0][1] = -3e6;
  }
  store.damage[1] = 0.5;
  store.damage[2] = 1;
  store.failed[2] = 1;
  std::ostringstream header, row;
  probes.write_header(header);
  probes.write_row(row, store);
  EXPECT_EQ(header.str(), ",probe_p_sxx,probe_p_sxy,probe_p_syy");
  const auto v = input::parse_doubles(row.str().substr(1), "probe row");
  ASSERT_EQ(v.size(), 3u);
  EXPECT_DOUBLE_EQ(v[0], 3e6);
  EXPECT_DOUBLE_EQ(v[1], -1.5e6);
  EXPECT_EQ(v[2], 0.0);
  // The one formula, which the particle files use too.
  EXPECT_EQ(effective_stress(store, 0), store.stress[0]);
  EXPECT_EQ(effective_stress(store, 1), 0.5 * store.stress[1]);
  EXPECT_EQ(effective_stress(store, 2).norm(), 0.0);
  store.damage[2] = 0.3; // failed whatever its damage
  EXPECT_EQ(effective_stress(store, 2).norm(), 0.0);
  const std::string dir = lme_mpm_test::scratch("effective_stress");
  std::filesystem::create_directories(dir);
  ParticleOutput<2>(dir, 1.0).write(store, 0);
  const std::string vtu = lme_mpm_test::file_text(dir + "/particles_00000.vtu");
  for (const char *field : {"stress_xx", "undamaged_stress_xx", "max_principal_stress"})
    EXPECT_NE(vtu.find(std::string("Name=\"") + field + "\""), std::string::npos)
        << field;
}

TEST(Output, PeakForceOfAPushingSetIsItsLargestMagnitudeWithItsSign)
{
  // The tension bar's right grip pushed in: its reaction on the bar is negative, and
  // the peak load is the most negative reaction, checked every step.
  const auto r = lme_mpm_test::run_scene(
      "tension_bar.prm", "push",
      {"Material 1/Fracture/Model=none", "Material 2/Fracture/Model=none",
       "Time/End time=1e-3", "Output/Peak force set=right:x",
       "Boundary conditions/Constraint 2/Velocity/Function expression="
       "if(t < tr, -v0*0.5*(1 - cos(pi*t/tr)), -v0); 0"});
  const auto h        = lme_mpm_test::read_history(lme_mpm_test::scratch_path("push"));
  const std::size_t f = lme_mpm_test::column(h.first, "force_right_x"),
                    u = lme_mpm_test::column(h.first, "displacement_right_x");
  double most         = 0;
  for (const auto &row : h.second)
    most = std::min(most, row[f]);
  ASSERT_LT(most, -10); // tens of newtons in compression
  EXPECT_LT(r.at("peak_force"), 0);
  // Every step is checked, the rows sample them (to 10 digits): at least the rows'
  // largest.
  EXPECT_LE(r.at("peak_force"), most * (1 - 1e-9));
  EXPECT_GT(r.at("peak_force"), 1.2 * most);
  EXPECT_LT(r.at("displacement_at_peak"), 0.5 * h.second.back()[u]);
}

TEST(Output, ANewRunRemovesAnEarlierRunsFilesFromItsDirectory)
{
  // A long run with many particle files, then a short one into the same directory:
  // no particle file is left that the new series does not list, and a file of the
  // user's own stays.
  const std::string dir                = lme_mpm_test::scratch_path("reuse");
  const std::vector<std::string> files = {"Output/Write particle files=true",
                                          "Output/Output interval=1e-6"};
  auto with                            = [&](const std::string &end)
  {
    auto o = files;
    o.push_back("Time/End time=" + end);
    return o;
  };
  lme_mpm_test::run_scene("tension_bar.prm", "reuse", with("3e-5"));
  const auto count = [&](const std::string &suffix)
  {
    unsigned int n = 0;
    for (const auto &e : std::filesystem::directory_iterator(dir))
    {
      const std::string name = e.path().filename().string();
      n += name.size() > suffix.size() &&
           name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
    }
    return n;
  };
  ASSERT_GE(count(".vtu"), 30u);
  std::ofstream(dir + "/notes.txt") << "mine";
  // run_scene() clears the directory itself: run into it directly.
  std::ostringstream console;
  auto o = with("5e-6");
  o.push_back("Output/Directory=" + dir);
  lme_mpm::run_parameter_file(lme_mpm_test::scene("tension_bar.prm"), o, console);
  const std::string pvd = lme_mpm_test::file_text(dir + "/particles.pvd");
  unsigned int listed   = 0;
  for (auto at = pvd.find("file=\""); at != std::string::npos;
       at      = pvd.find("file=\"", at + 1))
    ++listed;
  EXPECT_GE(listed, 5u);
  EXPECT_EQ(count(".vtu"), listed);
  EXPECT_TRUE(std::filesystem::exists(dir + "/notes.txt"));
  EXPECT_NE(console.str().find("files of an earlier run"), std::string::npos)
      << console.str();
  EXPECT_TRUE(is_run_file("particles_00012.vtu"));
  EXPECT_TRUE(is_run_file("particles_00012.3.vtu"));
  EXPECT_TRUE(is_run_file("checkpoint.1.bin.prev"));
  EXPECT_FALSE(is_run_file("particles_final.vtu"));
  EXPECT_FALSE(is_run_file("notes.txt"));
}
