// What the scenes measure on their particles: the crack from a notch, the Rayleigh
// speed that scales its speed.
#include <gtest/gtest.h>

#include <lme_mpm/scenes/scene_tools.h>

#include <cmath>

using namespace lme_mpm;

namespace
{
/// A 2D block of particles 1 mm apart (thickness 0.1 m), x in [0, 20) mm, y in
/// [0, 30) mm, body 0.
ParticleStore<2> block()
{
  ParticleStore<2> p;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 30; ++j)
      p.add(Point<2>(1e-3 * (i + 0.5), 1e-3 * (j + 0.5)), 1.0, 1e-6 * 0.1, 0, 0);
  return p;
}

void damage_column(ParticleStore<2> &p, const double x, const double y0, const double y1)
{
  for (std::size_t i = 0; i < p.size(); ++i)
    if (std::abs(p.reference_position[i][0] - x) < 1e-9 &&
        p.reference_position[i][1] > y0 && p.reference_position[i][1] < y1)
      p.damage[i] = 1;
}
} // namespace

TEST(SceneTools, CrackTipFollowsOnlyTheCrackFromTheNotch)
{
  ParticleStore<2> p         = block();
  const Point<2> notch_tip   = {0.0105, 0.0};
  const Tensor<1, 2> upwards = Tensor<1, 2>({0.0, 1.0});
  const auto tip             = [&]()
  { return scenes::crack_tip_distance(p, 0, 0.1, notch_tip, upwards); };
  EXPECT_EQ(tip(), 0);
  // A crack elsewhere (from the top face down to y = 20 mm) is not the notch's.
  damage_column(p, 0.0035, 0.020, 1);
  EXPECT_EQ(tip(), 0);
  // The crack from the notch tip up to the particle at y = 12.5 mm.
  damage_column(p, 0.0105, 0, 0.013);
  EXPECT_NEAR(tip(), 0.0125, 1e-12);
  // Partly damaged particles above do not count; once they fail they do, and a
  // particle of another body never does.
  for (std::size_t i = 0; i < p.size(); ++i)
    if (std::abs(p.reference_position[i][0] - 0.0105) < 1e-9 &&
        p.reference_position[i][1] > 0.013 && p.reference_position[i][1] < 0.016)
      p.damage[i] = 0.9;
  EXPECT_NEAR(tip(), 0.0125, 1e-12);
  damage_column(p, 0.0105, 0.013, 0.016);
  EXPECT_NEAR(tip(), 0.0155, 1e-12);
  for (std::size_t i = 0; i < p.size(); ++i)
    if ((p.reference_position[i] - Point<2>(0.0105, 0.0165)).norm() < 1e-9)
      p.body_id[i] = 1, p.damage[i] = 1;
  EXPECT_NEAR(tip(), 0.0155, 1e-12);
  // The two cracks joined: the tip is the top of the other one.
  damage_column(p, 0.0045, 0.014, 0.021);
  damage_column(p, 0.0055, 0.013, 0.016);
  for (const double x : {0.0065, 0.0075, 0.0085, 0.0095})
    damage_column(p, x, 0.014, 0.016);
  EXPECT_NEAR(tip(), 0.0295, 1e-12);
}

TEST(SceneTools, CrackTipFollowsACrackThroughCellsTwiceAsTallAsWide)
{
  // Cells 1.25 mm wide and 2.5 mm tall with two particles per direction at the
  // Gauss points (0.211 and 0.789 of the cell), as the drop-weight ligament has
  // them: a column of failed particles steps 1.056 and 1.444 mm upwards, 1.63 times
  // the particles' size (their area's side, 0.884 mm).
  const double w = 1.25e-3, h = 2.5e-3, g = 0.5 - 0.5 / std::sqrt(3.0);
  ParticleStore<2> p;
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 12; ++j)
      for (const double a : {g, 1 - g})
        for (const double b : {g, 1 - g})
          p.add(Point<2>(w * (i + a), h * (j + b)), 1.0, 0.25 * w * h * 0.1, 0, 0);
  const double x         = w * (4 + g);
  const auto fail_column = [&](const double y0, const double y1, const double d)
  {
    for (std::size_t i = 0; i < p.size(); ++i)
      if (std::abs(p.reference_position[i][0] - x) < 1e-9 &&
          p.reference_position[i][1] > y0 && p.reference_position[i][1] < y1)
        p.damage[i] = d;
  };
  const Point<2> notch_tip(x, 0.0);
  const auto tip = [&]() {
    return scenes::crack_tip_distance(p, 0, 0.1, notch_tip, Tensor<1, 2>({0.0, 1.0}));
  };
  fail_column(0, 0.02, 1);
  // The highest particle below 20 mm: cell 7, upper Gauss point.
  EXPECT_NEAR(tip(), h * (7 + 1 - g), 1e-12);
  // One intact particle stops it: the crack above is not the notch's.
  fail_column(h * 3, h * 3 + 0.5 * h, 0);
  EXPECT_NEAR(tip(), h * (2 + 1 - g), 1e-12);
}

TEST(SceneTools, RayleighSpeedSolvesTheRayleighEquation)
{
  // A Poisson solid (nu = 0.25): c_R / c_s = sqrt(2 - 2 / sqrt(3)) = 0.9194.
  const double E = 2.5, rho = 1.0, cs = std::sqrt(E / (2 * rho * 1.25));
  EXPECT_NEAR(scenes::rayleigh_wave_speed(E, 0.25, rho, false) / cs,
              std::sqrt(2 - 2 / std::sqrt(3.0)), 1e-12);
  // Incompressible: 0.9553 c_s, the root of x^3 - 8 x^2 + 24 x - 16 = 0 in x = (c/cs)^2.
  EXPECT_NEAR(scenes::rayleigh_wave_speed(E, 0.5, rho, false) /
                  std::sqrt(E / (2 * rho * 1.5)),
              0.955313, 1e-6);
  // Plane stress acts as a solid of Poisson's ratio nu / (1 + nu): the same speed as
  // plane strain with nu' = 0.2 / 1.2 and the same shear modulus.
  const double nu = 0.2, nu_eff = nu / (1 + nu), E_eff = E * (1 + nu_eff) / (1 + nu);
  EXPECT_NEAR(scenes::rayleigh_wave_speed(E, nu, rho, true),
              scenes::rayleigh_wave_speed(E_eff, nu_eff, rho, false), 1e-12);
}

TEST(SceneTools, LoadTestStopsOnlyOnceTheSpecimenSoftens)
{
  // A load that dips below the fraction of its peak while nothing has softened (the
  // contact forming under a roller) does not end the run; the same dip after softening
  // began does.
  ParticleStore<2> p = block();
  std::vector<Tensor<1, 2>> force(1, Tensor<1, 2>({0.0, -1.0}));
  std::vector<double> peak(1, 5.0);
  SceneState<2> state;
  state.particles           = &p;
  state.contact_forces      = &force;
  state.peak_contact_forces = &peak;
  EXPECT_EQ(scenes::load_fell_below(state, 0, 0.3), "");
  p.damage[17] = 1e-6;
  EXPECT_NE(scenes::load_fell_below(state, 0, 0.3), "");
  // Above the fraction, or with a fraction of 0, it goes on.
  force[0] = Tensor<1, 2>({0.0, -2.0});
  EXPECT_EQ(scenes::load_fell_below(state, 0, 0.3), "");
  EXPECT_EQ(scenes::load_fell_below(state, 0, 0.0), "");
}

TEST(SceneTools, CrackBandMeasuresTheWidthAndTheEnergyOffTheCrack)
{
  // A crack three particle columns wide (x = 9.5, 10.5, 11.5 mm) from the bottom face
  // to y = 25 mm, each of its particles dissipating 1 J, and a patch of four particles
  // far from it dissipating 2 J each with damage below the path's threshold.
  ParticleStore<2> p = block();
  for (const double x : {0.0095, 0.0105, 0.0115})
    damage_column(p, x, 0, 0.025);
  double on = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.damage[i] > 0)
      p.dissipated[i] = 1, on += 1;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.reference_position[i][0] < 0.002 && p.reference_position[i][1] > 0.028)
      p.damage[i] = 0.3, p.dissipated[i] = 2;
  const scenes::CrackPath path = scenes::crack_path(p, 0, 0.1, 0.5);
  ASSERT_EQ(path.widths.size(), 25u);
  EXPECT_NEAR(path.spacing, 1e-3, 1e-12);
  EXPECT_NEAR(path.length(), 0.025, 1e-12);
  const scenes::CrackBand band =
      scenes::crack_band(p, 0, path, {Point<2>(0.0105, 0), Point<2>(0.0105, 0.025)});
  EXPECT_NEAR(band.width, 0.003, 1e-12);
  EXPECT_NEAR(band.dissipated, on + 8, 1e-12);
  EXPECT_NEAR(band.on_crack, on, 1e-12);
  EXPECT_NEAR(band.off_crack_share, 8 / (on + 8), 1e-12);
  // Particles of another body count nowhere.
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.reference_position[i][1] > 0.028)
      p.body_id[i] = 1;
  const std::vector<Point<2>> line = {Point<2>(0.0105, 0), Point<2>(0.0105, 0.025)};
  EXPECT_NEAR(scenes::crack_band(p, 0, path, line).off_crack_share, 0, 1e-12);
}

TEST(SceneTools, CrackPlaneDeviationIsTheRmsDistanceFromTheBestPlane)
{
  // 2D: a crack two particle columns wide (x = 10.5 and 11.5 mm) lies 0.5 mm either
  // side of its best line: 0.25 of a 2 mm cell.
  ParticleStore<2> p = block();
  EXPECT_EQ(scenes::crack_plane_deviation(p, 0, 0.002), 0);
  damage_column(p, 0.0105, 0, 0.030);
  damage_column(p, 0.0115, 0, 0.030);
  EXPECT_NEAR(scenes::crack_plane_deviation(p, 0, 0.002), 0.25, 1e-12);
  // Partly damaged particles, and failed ones of another body, are not the crack's.
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.reference_position[i][0] < 0.003)
      p.damage[i] = 0.9;
    else if (p.reference_position[i][0] > 0.017)
      p.damage[i] = 1, p.body_id[i] = 1;
  EXPECT_NEAR(scenes::crack_plane_deviation(p, 0, 0.002), 0.25, 1e-12);
  // A branch off the crack reads more than the straight crack.
  damage_column(p, 0.0045, 0.020, 0.030);
  EXPECT_GT(scenes::crack_plane_deviation(p, 0, 0.002), 0.5);

  // 3D: two layers of particles a = 0.3 mm either side of a plane turned out of every
  // grid plane, far from the origin: the deviation is a over the cell, whatever the
  // plane's size and place.
  const double a = 3e-4;
  Tensor<1, 3> n({1.0, 2.0, -2.0}), t1({2.0, -1.0, 0.0});
  n /= n.norm(), t1 /= t1.norm();
  const Tensor<1, 3> t2 = cross_product_3d(n, t1);
  const Point<3> origin(5.0, -3.0, 7.0);
  ParticleStore<3> q;
  for (int i = -10; i <= 10; ++i)
    for (int j = -6; j <= 6; ++j)
      for (const double s : {-a, a})
      {
        const std::size_t k =
            q.add(origin + 1e-3 * (i * t1 + 1.5 * j * t2) + s * n, 1.0, 1e-9, 0, 0);
        q.damage[k] = 1;
      }
  EXPECT_NEAR(scenes::crack_plane_deviation(q, 0, 0.0025), a / 0.0025, 1e-9);
}
