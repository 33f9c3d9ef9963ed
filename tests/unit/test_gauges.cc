// Opening gauges (Output/Opening gauges) read the exact opening of a homogeneous
// deformation, leave prescribed bodies and ghosts out, and reject bad lists.
#include <gtest/gtest.h>
#include <lme_mpm/base/input.h>
#include <lme_mpm/output/gauges.h>

#include <deal.II/base/parameter_handler.h>

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
  prm.set("Opening gauges", "diagonal: " + a + ", " + b + "; upright: " + c + ", " + d);
  prm.set("Gauge radius", "0.06");
  prm.leave_subsection();
  OpeningGauges<dim> gauges;
  gauges.parse_parameters(prm, 0.1);
  ASSERT_EQ(gauges.size(), 2u);
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
