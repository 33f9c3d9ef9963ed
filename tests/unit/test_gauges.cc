// Opening gauges (Output/Opening gauges) read the exact opening of a homogeneous
// deformation, leave prescribed bodies and ghosts out, and reject bad lists.
#include <gtest/gtest.h>
#include <lme_mpm/base/input.h>
#include <lme_mpm/output/gauges.h>
#include <lme_mpm/output/probes.h>

#include <deal.II/base/parameter_handler.h>

#include <sstream>
#include <string>

using namespace lme_mpm;

namespace
{
/// Particles on a lattice of spacing @p s filling [0, 1]^dim, moved by x = F X + c.
template <int dim>
ParticleStore<dim> deformed_lattice(const Tensor<2, dim> &F, const double s)
{
  ParticleStore<dim> p;
  const unsigned int n     = static_cast<unsigned int>(std::round(1 / s));
  const unsigned int total = dim == 2 ? n * n : n * n * n;
  Tensor<1, dim> c;
  c[0] = 0.3;
  for (unsigned int k = 0; k < total; ++k)
  {
    Point<dim> X;
    unsigned int rest = k;
    for (unsigned int d = 0; d < dim; ++d, rest /= n)
      X[d] = (rest % n + 0.5) * s;
    const std::size_t i     = p.add(X, 1.0, s * s, 0, 0);
    p.reference_position[i] = X;
    p.position[i]           = Point<dim>(F * X + c);
  }
  return p;
}

template <int dim>
void check_homogeneous()
{
  Tensor<2, dim> F;
  for (unsigned int i = 0; i < dim; ++i)
    for (unsigned int j = 0; j < dim; ++j)
      F[i][j] = (i == j ? 1.0 : 0.0) + 0.01 * (1 + i) + 0.02 * j * (i + 1);
  const double s       = 0.05;
  ParticleStore<dim> p = deformed_lattice<dim>(F, s);
  dealii::ParameterHandler prm;
  OpeningGauges<dim>::declare_parameters(prm);
  // Points at lattice sites, so that the particles within the radius lie symmetric
  // about them and their mean displacement is the displacement at the point.
  const std::string a = dim == 2 ? "0.275, 0.325" : "0.275, 0.325, 0.475";
  const std::string b = dim == 2 ? "0.725, 0.625" : "0.725, 0.625, 0.525";
  const std::string c = dim == 2 ? "0.475, 0.175" : "0.475, 0.175, 0.275";
  const std::string d = dim == 2 ? "0.475, 0.875" : "0.475, 0.875, 0.275";
  prm.enter_subsection("Output");
  // "wide" has a radius of its own; in 3D "column" stands for lines along z through
  // (0.275, 0.325) and (0.725, 0.625), averaging through the lattice's depth.
  std::string list = "diagonal: " + a + ", " + b + "; upright: " + c + ", " + d +
                     "; wide: " + c + ", " + d + ", 0.11";
  if (dim == 3)
    list += "; column: 0.275, 0.325, 0.725, 0.625";
  prm.set("Opening gauges", list);
  prm.set("Gauge radius", "0.06");
  prm.leave_subsection();
  OpeningGauges<dim> gauges;
  gauges.parse_parameters(prm, 0.1);
  ASSERT_EQ(gauges.size(), dim == 2 ? 3u : 4u);
  gauges.check(p, nullptr);
  const std::vector<double> w = gauges.read(p, nullptr);
  const auto exact            = [&](const std::string &from, const std::string &to)
  {
    const Point<dim> A      = input::parse_point<dim>(from, "A"),
                     B      = input::parse_point<dim>(to, "B");
    const Tensor<1, dim> AB = B - A;
    Tensor<2, dim> H        = F;
    for (unsigned int i = 0; i < dim; ++i)
      H[i][i] -= 1;
    return (H * AB) * AB / AB.norm();
  };
  EXPECT_NEAR(w[0], exact(a, b), 1e-12);
  EXPECT_NEAR(w[1], exact(c, d), 1e-12);
  EXPECT_GT(std::abs(w[0]), 1e-3);
  EXPECT_NEAR(w[2], exact(c, d), 1e-12);
  // Its radius, 2.2 lattice spacings, holds the sites with i^2 + j^2 (+ k^2) <= 4 about
  // the point: 13 in 2D, 33 in 3D (unit masses); the shared 0.06 holds 5 and 7.
  EXPECT_DOUBLE_EQ(gauges.mass_near(2, 0, p), dim == 2 ? 13.0 : 33.0);
  EXPECT_DOUBLE_EQ(gauges.mass_near(1, 0, p), dim == 2 ? 5.0 : 7.0);
  if (dim == 3)
  {
    // The opening between two lines: the displacement gradient along their x-y
    // direction, the means over the depth taken at the lattice's mid-depth.
    Tensor<1, dim> AB;
    AB[0] = 0.45, AB[1] = 0.3;
    Tensor<2, dim> H = F;
    for (unsigned int i = 0; i < dim; ++i)
      H[i][i] -= 1;
    EXPECT_NEAR(w[3], (H * AB) * AB / AB.norm(), 1e-12);
  }

  // A prescribed body's particles and ghosts are not gauged: moving them changes
  // nothing.
  std::vector<std::uint8_t> excluded = {0, 1};
  gauges.set_excluded_bodies(excluded);
  const Point<dim> A   = input::parse_point<dim>(a, "A");
  std::size_t moved    = 0;
  const std::size_t n0 = p.size();
  for (std::size_t i = 0; i < n0; ++i)
    if (p.reference_position[i].distance(A) < 0.06)
    {
      const std::size_t j     = p.add(p.position[i], 5.0, s * s, 0, (moved % 2) ? 1 : 0);
      p.reference_position[j] = p.reference_position[i];
      p.position[j][0] += 0.1;
      p.ghost[j] = (moved % 2) ? 0 : 1;
      ++moved;
    }
  ASSERT_GT(moved, 2u);
  const std::vector<double> again = gauges.read(p, nullptr);
  EXPECT_DOUBLE_EQ(again[0], w[0]);
  EXPECT_DOUBLE_EQ(again[1], w[1]);
}
} // namespace

TEST(OpeningGauges, ReadTheExactOpeningOfAHomogeneousDeformation2D)
{
  check_homogeneous<2>();
}

TEST(OpeningGauges, ReadTheExactOpeningOfAHomogeneousDeformation3D)
{
  check_homogeneous<3>();
}

TEST(OpeningGauges, EmptyListHasNoGaugeAndAGaugeOffTheBodiesIsRejected)
{
  dealii::ParameterHandler prm;
  OpeningGauges<2>::declare_parameters(prm);
  OpeningGauges<2> gauges;
  gauges.parse_parameters(prm, 0.1);
  EXPECT_TRUE(gauges.empty());
  prm.enter_subsection("Output");
  prm.set("Opening gauges", "far: 2, 2, 3, 3");
  prm.leave_subsection();
  gauges.parse_parameters(prm, 0.1);
  Tensor<2, 2> F;
  F[0][0] = F[1][1]        = 1;
  const ParticleStore<2> p = deformed_lattice<2>(F, 0.1);
  EXPECT_THROW(gauges.check(p, nullptr), ExcBadInput);
}

TEST(Probes, ReadTheExactMeansOfAHomogeneousDeformation)
{
  // x = F X + c, velocity and damage affine in X: the particles within the radius of
  // the image of the lattice's centre are symmetric about it, so each mean is the
  // field's value there, exactly up to rounding.
  Tensor<2, 2> F;
  F[0][0] = 1.002, F[0][1] = 0.0005, F[1][0] = -0.0003, F[1][1] = 0.999;
  ParticleStore<2> p = deformed_lattice<2>(F, 0.02);
  Tensor<2, 2> L;
  L[0][0] = 2, L[0][1] = -1, L[1][0] = 0.5, L[1][1] = 3;
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    p.velocity[i] = L * p.reference_position[i];
    p.damage[i]   = 0.2 + 0.5 * p.reference_position[i][0];
  }
  const Point<2> X0(0.5, 0.5);
  Tensor<1, 2> c;
  c[0]                  = 0.3;
  const Point<2> centre = Point<2>(F * X0 + c);
  ParameterHandler prm;
  Probes<2>::declare_parameters(prm, 2);
  prm.enter_subsection("Output");
  prm.enter_subsection("Probe 1");
  prm.set("Name", "g");
  prm.set("Point", std::to_string(centre[0]) + ", " + std::to_string(centre[1]));
  prm.set("Radius", "0.1");
  prm.set("Quantities", "displacement, velocity, damage");
  prm.leave_subsection();
  prm.enter_subsection("Probe 2");
  prm.set("Name", "s");
  prm.set("Point", std::to_string(centre[0]) + ", " + std::to_string(centre[1]));
  prm.leave_subsection();
  prm.leave_subsection();
  Probes<2> probes;
  probes.parse_parameters(prm, 2);
  std::ostringstream header, row;
  probes.write_header(header);
  probes.write_row(row, p);
  EXPECT_EQ(header.str(), ",probe_g_ux,probe_g_uy,probe_g_vx,probe_g_vy,probe_g_damage,"
                          "probe_s_sxx,probe_s_sxy,probe_s_syy");
  const auto v = input::parse_doubles(row.str().substr(1), "probe row");
  ASSERT_EQ(v.size(), 8u);
  // The point was printed to 6 digits: the centre it selects is exact to about 1e-6,
  // and the set stays symmetric as long as no particle sits on the radius.
  const Point<2> Xc(0.5, 0.5);
  const Tensor<1, 2> u = F * Xc + c - Xc, w = L * Xc;
  EXPECT_NEAR(v[0], u[0], 1e-12);
  EXPECT_NEAR(v[1], u[1], 1e-12);
  EXPECT_NEAR(v[2], w[0], 1e-12);
  EXPECT_NEAR(v[3], w[1], 1e-12);
  EXPECT_NEAR(v[4], 0.2 + 0.5 * 0.5, 1e-12);
  // Bad input: nothing to report.
  prm.enter_subsection("Output");
  prm.enter_subsection("Probe 1");
  prm.set("Quantities", "");
  prm.leave_subsection();
  prm.leave_subsection();
  try
  {
    probes.parse_parameters(prm, 2);
    ADD_FAILURE() << "an empty Quantities was accepted";
  }
  catch (const std::exception &e)
  {
    EXPECT_NE(std::string(e.what()).find("Output/Probe 1/Quantities"), std::string::npos);
  }
}
