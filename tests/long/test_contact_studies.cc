// Contact refinement studies: the discs' energy loss and the disc drop.
#include <gtest/gtest.h>

#include <lme_mpm/simulation/run.h>
#include <lme_mpm/simulation/simulation.h>

#include "test_helpers.h"

#include <cmath>

using namespace lme_mpm;

TEST(Contact, DiscEnergyLossFallsWithTheCellSize)
{
  // Each node that comes into contact stops its fields' approach at once, a small
  // perfectly plastic impact of the node masses: the energy lost falls with h.
  const auto energy_lost = [](const std::string &h)
  {
    const auto r =
        lme_mpm_test::run_scene("two_disk_collision.prm", "disc_energy_" + h,
                                {"Contact/Type=multi-field", "Grid/Cell size=" + h,
                                 "Time/End time=2", "Output/Write particle files=false"});
    return r.at("max_energy_drift");
  };
  const double coarse = energy_lost("0.025"), fine = energy_lost("0.0125");
  std::cout << "two discs with contact (LME): max energy drift " << coarse
            << " at h = 0.025, " << fine << " at h = 0.0125" << std::endl;
  EXPECT_LT(fine, 0.6 * coarse);
}

TEST(Contact, DiscEnergyLossBelowOnePercentWithBsplinesAt32CellsPerRadius)
{
  // The loss falls with h (B-splines, projected exchange: 5.1 %, 2.3 %, 0.79 % at h =
  // 0.025, 0.0125, 0.00625 m; discs of radius 0.2 m): at 32 cells per radius it is
  // below 1 % over the whole run (collision and separation).
  const auto r = lme_mpm_test::run_scene(
      "two_disk_collision.prm", "disc_energy_bspline",
      {"Contact/Type=multi-field", "Shape functions/Type=bspline",
       "Grid/Cell size=0.00625", "Output/Write particle files=false"});
  std::cout << "two discs with contact (B-splines, h = 0.00625): max energy drift "
            << r.at("max_energy_drift") << std::endl;
  EXPECT_LT(r.at("max_energy_drift"), 0.01);
}

namespace
{
/// A disc-drop run: the slab's force averaged over 1 ms windows, and the disc's mean
/// vertical velocity over the last 1 ms (the rebound).
struct DropRun
{
  std::vector<double> force;
  double rebound = 0;
};

DropRun drop(const std::string &h)
{
  const std::string tag = "drop_" + h;
  lme_mpm_test::run_scene("disc_drop.prm", tag,
                          {"Grid/Cell size=" + h, "Time/End time=0.03"});
  const auto hist = lme_mpm_test::read_history(lme_mpm_test::scratch_path(tag));
  const auto col  = [&](const std::string &name)
  { return std::find(hist.first.begin(), hist.first.end(), name) - hist.first.begin(); };
  // The interval means: ten rows of 0.1 ms make a 1 ms mean of the impulse.
  const auto f = col("force_slab_mean_y"), y = col("displacement_disc_y");
  DropRun out;
  out.force.assign(30, 0.0);
  std::vector<unsigned int> count(30, 0);
  for (const auto &row : hist.second)
  {
    const unsigned int w = std::min(29u, static_cast<unsigned int>(row[1] / 1e-3));
    out.force[w] += row[f], ++count[w];
  }
  for (unsigned int w = 0; w < 30; ++w)
    out.force[w] /= std::max(1u, count[w]);
  const auto &last = hist.second.back(), &before = hist.second[hist.second.size() - 11];
  out.rebound = (last[y] - before[y]) / (last[1] - before[1]);
  return out;
}

double relative_difference(const std::vector<double> &a, const std::vector<double> &b)
{
  double d = 0, n = 0;
  for (unsigned int i = 0; i < a.size(); ++i)
    d += (a[i] - b[i]) * (a[i] - b[i]), n += b[i] * b[i];
  return std::sqrt(d / n);
}
} // namespace

TEST(Contact, DiscDropConvergesUnderRefinement)
{
  // An elastic cylinder hitting a rigid flat has no closed-form history; the
  // reference is the run at a quarter of the cell size.
  const DropRun coarse = drop("0.00625"), mid = drop("0.003125"),
                fine    = drop("0.0015625");
  const double e_coarse = relative_difference(coarse.force, fine.force),
               e_mid    = relative_difference(mid.force, fine.force);
  std::cout << "disc drop: slab force (1 ms means) differs from h = 1.5625 mm by "
            << e_coarse << " at h = 6.25 mm, " << e_mid
            << " at 3.125 mm; rebound velocity " << coarse.rebound << ", " << mid.rebound
            << ", " << fine.rebound << " m/s (impact at 1 m/s)" << std::endl;
  EXPECT_LT(e_mid, 0.5 * e_coarse);
  EXPECT_LT(std::abs(mid.rebound - fine.rebound),
            0.5 * std::abs(coarse.rebound - fine.rebound));
  // The disc leaves upwards, slower than it came.
  EXPECT_GT(fine.rebound, 0.5);
  EXPECT_LT(fine.rebound, 1.0);
}
