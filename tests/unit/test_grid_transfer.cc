// GridTransfer on its own: the scatter conserves mass and momentum, a uniform motion
// stays uniform on the grid and strains nothing, internal forces sum to zero, and the
// sums do not depend on the thread count.
#include <deal.II/base/multithread_info.h>

#include <gtest/gtest.h>

#include <lme_mpm/solver/grid_transfer.h>

#include <memory>
#include <random>

using namespace lme_mpm;

namespace
{
/// A graded 2D grid and random particles inside its middle, with random stresses.
struct Scatter
{
  BackgroundGrid<2> grid;
  ParticleStore<2> particles;
  std::unique_ptr<ShapeFunction<2>> functions;

  explicit Scatter(const std::string &family, const Tensor<1, 2> &velocity = {})
  {
    std::vector<double> x(12, 0.1), y = {0.2, 0.1, 0.1, 0.05, 0.05, 0.05, 0.1, 0.1, 0.2};
    grid.reinit(Point<2>(0, 0), {{x, y}});
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> ux(0.35, 0.85), uy(0.35, 0.75), u(-1, 1);
    for (unsigned int p = 0; p < 400; ++p)
    {
      const std::size_t i =
          particles.add(Point<2>(ux(rng), uy(rng)), 0.5 + 0.5 * u(rng), 1e-3, 0, 0);
      particles.velocity[i] = velocity;
      for (unsigned int a = 0; a < 2; ++a)
        for (unsigned int b = a; b < 2; ++b)
          particles.stress[i][a][b] = 1e3 * u(rng);
    }
    for (std::size_t p = 0; p < particles.size(); ++p)
      particles.id[p] = p;
    dealii::ParameterHandler prm;
    ShapeFunctionRegistry<2>::instance().declare_all(prm);
    ShapeFunctionContext<2> context;
    context.grid = &grid;
    functions    = ShapeFunctionRegistry<2>::instance().create(family, prm, context);
  }

  /// Particles to grid with a transfer built for the current thread limit.
  std::unique_ptr<GridTransfer<2>> transfer()
  {
    auto t = std::make_unique<GridTransfer<2>>(grid, particles);
    t->nodes().layout.reinit(grid.n_nodes());
    EXPECT_EQ(t->locate_and_sort(), particles.size());
    t->particles_to_grid(*functions, {}, [](std::size_t, std::size_t) {});
    return t;
  }
};

class Families : public ::testing::TestWithParam<std::string>
{
};
} // namespace

TEST_P(Families, ScatterConservesMassAndMomentum)
{
  Scatter s(GetParam(), Tensor<1, 2>({0.3, -1.2}));
  const auto transfer = s.transfer();
  double m_p = 0, m_I = 0;
  Tensor<1, 2> p_p, p_I;
  for (std::size_t p = 0; p < s.particles.size(); ++p)
    m_p += s.particles.mass[p], p_p += s.particles.mass[p] * s.particles.velocity[p];
  for (const unsigned int I : transfer->nodes().active)
    m_I += transfer->nodes().mass[I], p_I += transfer->nodes().momentum[I];
  EXPECT_NEAR(m_I, m_p, 1e-13 * m_p);
  EXPECT_NEAR((p_I - p_p).norm(), 0, 1e-13 * p_p.norm());
}

TEST_P(Families, UniformMotionStaysUniformAndStrainsNothing)
{
  const Tensor<1, 2> v({0.3, -1.2});
  Scatter s(GetParam(), v);
  const auto transfer = s.transfer();
  ExplicitNewmark newmark;
  transfer->predict_rates(newmark, 1e-4, 1e-20);
  for (const unsigned int I : transfer->nodes().active)
    EXPECT_NEAR((transfer->nodes().rate[I] - v).norm(), 0, 1e-12);
  transfer->strain_increments(0, s.particles.size(), 1e-4);
  for (std::size_t p = 0; p < s.particles.size(); ++p)
    EXPECT_LT(s.particles.strain_increment[p].norm(), 1e-15);
}

TEST_P(Families, InternalForcesSumToTheBodyForce)
{
  Scatter s(GetParam());
  const auto transfer = s.transfer();
  const Tensor<1, 2> g({0, -9.81});
  transfer->scatter_chunks([&](const std::size_t b, const std::size_t e)
                           { transfer->forces(b, e, g); });
  Tensor<1, 2> total, weight;
  for (const unsigned int I : transfer->nodes().active)
    total += transfer->nodes().force[I];
  for (std::size_t p = 0; p < s.particles.size(); ++p)
    weight += s.particles.mass[p] * g;
  // Gradients of a partition of unity sum to zero: the stresses add no net force.
  EXPECT_NEAR((total - weight).norm(), 0, 1e-9 * weight.norm());
}

INSTANTIATE_TEST_SUITE_P(GridTransfer, Families,
                         ::testing::Values("linear", "ugimp", "lme"),
                         [](const auto &info) { return info.param; });

TEST(GridTransfer, SumsDoNotDependOnTheThreadCount)
{
  std::vector<std::vector<double>> masses;
  for (const unsigned int threads : {1u, 2u, 4u})
  {
    dealii::MultithreadInfo::set_thread_limit(threads);
    Scatter s("lme", Tensor<1, 2>({1, 2}));
    const auto transfer   = s.transfer();
    std::vector<double> m = transfer->nodes().mass;
    for (const auto &p : transfer->nodes().momentum)
      m.push_back(p[0]), m.push_back(p[1]);
    masses.push_back(m);
  }
  dealii::MultithreadInfo::set_thread_limit();
  EXPECT_EQ(masses[0], masses[1]);
  EXPECT_EQ(masses[0], masses[2]);
}
