// GridTransfer on its own: the scatter conserves mass and momentum, a uniform motion
// stays uniform on the grid and strains nothing, internal forces sum to zero, and the
// sums do not depend on the thread count. The consistent mass assembled from its
// connectivity equals the dense sum, its solve a dense solve.
#include <deal.II/base/multithread_info.h>

#include <gtest/gtest.h>

#include <deal.II/lac/full_matrix.h>

#include <lme_mpm/solver/grid_transfer.h>
#include <lme_mpm/solver/mass_solve.h>

#include <cmath>
#include <iostream>
#include <map>
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
    // B-splines need a uniform grid.
    std::vector<double> x(12, 0.1), y = {0.2, 0.1, 0.1, 0.05, 0.05, 0.05, 0.1, 0.1, 0.2};
    if (family == "bspline")
      y.assign(9, 0.1);
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

  /// Particles to grid with a transfer built for the current thread limit; rows in
  /// full, or as their factors where the family allows it (@p full_rows false).
  std::unique_ptr<GridTransfer<2>> transfer(const bool full_rows = true)
  {
    auto t = std::make_unique<GridTransfer<2>>(grid, particles);
    t->nodes().layout.reinit(grid.n_nodes());
    EXPECT_EQ(t->locate_and_sort(), particles.size());
    t->particles_to_grid(
        *functions, {}, [](std::size_t, std::size_t) {}, full_rows);
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

TEST(GridTransfer, RowsKeptAsFactorsGiveTheFullRowsStepToTheBit)
{
  // A whole step's transfers (scatter, strains, forces, the particle update) with the
  // tensor-product families' rows in full and as their factors (linear: as the cells
  // alone, the rows formed again by each walk): every nodal and
  // particle value equal to the bit (graded grids for linear and uGIMP).
  for (const std::string family : {"linear", "ugimp", "bspline"})
  {
    std::vector<std::vector<double>> results;
    for (const bool full_rows : {true, false})
    {
      Scatter s(family, Tensor<1, 2>({0.3, -1.2}));
      for (std::size_t p = 0; p < s.particles.size(); ++p)
        s.particles.velocity[p][0] += 0.1 * std::sin(7 * s.particles.position[p][1]);
      const auto transfer = s.transfer(full_rows);
      // Linear rows are kept as the particles' cells (Linear::rows_are_cell_hats()).
      const Connectivity<2> &conn = transfer->connectivity();
      EXPECT_EQ(conn.factor_width, full_rows            ? 0u
                                   : family == "linear" ? 2u
                                                        : 4u)
          << family;
      EXPECT_EQ(conn.hat_rows_from_cells, !full_rows && family == "linear") << family;
      ExplicitNewmark newmark;
      const double dt = 1e-4;
      transfer->predict_rates(newmark, dt, 1e-20);
      transfer->strain_increments(0, s.particles.size(), dt);
      const Tensor<1, 2> g({0, -9.81});
      transfer->scatter_chunks([&](const std::size_t b, const std::size_t e)
                               { transfer->forces(b, e, g); });
      transfer->accelerations(1e-20);
      std::size_t bad   = 0;
      double fastest    = 0;
      const double work = transfer->grid_to_particles(newmark, dt, g, 1.0, bad, fastest);
      std::vector<double> r = {work, fastest, double(bad)};
      const auto &nodes     = transfer->nodes();
      for (const unsigned int I : nodes.active)
        for (unsigned int d = 0; d < 2; ++d)
          r.insert(r.end(), {nodes.mass[I], nodes.momentum[I][d], nodes.force[I][d],
                             nodes.rate[I][d]});
      for (std::size_t p = 0; p < s.particles.size(); ++p)
        for (unsigned int d = 0; d < 2; ++d)
          r.insert(r.end(), {s.particles.position[p][d], s.particles.velocity[p][d],
                             s.particles.strain[p][d][d], s.particles.strain[p][0][1]});
      results.push_back(r);
    }
    ASSERT_EQ(results[0].size(), results[1].size()) << family;
    std::size_t differ = 0;
    for (std::size_t k = 0; k < results[0].size(); ++k)
      differ += results[0][k] != results[1][k];
    EXPECT_EQ(differ, 0u) << family;
  }
}

/// The mass matrix tests run on every family (B-splines included).
class MassFamilies : public ::testing::TestWithParam<std::string>
{
};

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

namespace
{
/// The dense consistent mass sum_p m_p N_Ip N_Jp over the fields of a transfer.
dealii::FullMatrix<double> dense_consistent_mass(const GridTransfer<2> &transfer,
                                                 const ParticleStore<2> &particles)
{
  const Connectivity<2> &conn = transfer.connectivity();
  const unsigned int n        = transfer.nodes().mass.size();
  dealii::FullMatrix<double> M(n, n);
  for (std::size_t p = 0; p < particles.size(); ++p)
    for (unsigned int a = 0; a < conn.n_nodes[p]; ++a)
      for (unsigned int b = 0; b < conn.n_nodes[p]; ++b)
        M(conn.nodes[p * conn.stride + a], conn.nodes[p * conn.stride + b]) +=
            particles.mass[p] * conn.N[p * conn.stride + a] * conn.N[p * conn.stride + b];
  return M;
}

/// The lumped-mass norm sqrt(sum_I m_I |v_I|^2) of v - w on the active fields.
double lumped_norm(const NodalFields<2> &fields, const std::vector<Tensor<1, 2>> &v,
                   const std::vector<Tensor<1, 2>> &w)
{
  double s = 0;
  for (const unsigned int I : fields.active)
    s += fields.mass[I] * (v[I] - w[I]).norm_square();
  return std::sqrt(s);
}
} // namespace

TEST_P(MassFamilies, AssembledConsistentMassEqualsTheDenseSum)
{
  Scatter s(GetParam());
  const auto transfer                    = s.transfer();
  const dealii::FullMatrix<double> dense = dense_consistent_mass(*transfer, s.particles);
  ConsistentMassMatrix<2> matrix;
  matrix.assemble(transfer->connectivity(), s.particles.mass, transfer->nodes().layout,
                  transfer->nodes().active);
  ASSERT_EQ(matrix.rows(), transfer->nodes().active);
  double largest       = 0;
  std::size_t nonzeros = 0;
  for (const unsigned int I : transfer->nodes().active)
    for (const unsigned int J : transfer->nodes().active)
      largest = std::max(largest, std::abs(dense(I, J))), nonzeros += dense(I, J) != 0;
  for (const unsigned int I : transfer->nodes().active)
    for (const unsigned int J : transfer->nodes().active)
      ASSERT_NEAR(matrix.entry(I, J), dense(I, J), 1e-12 * largest) << I << ", " << J;
  EXPECT_EQ(matrix.n_nonzeros(), nonzeros);
  // Rows sum to the lumped mass (a partition of unity).
  std::vector<Tensor<1, 2>> ones(dense.m(), Tensor<1, 2>({1, 1})), product(dense.m());
  matrix.vmult(ones, product);
  for (const unsigned int I : transfer->nodes().active)
    EXPECT_NEAR(product[I][0], transfer->nodes().mass[I], 1e-12 * largest);
}

TEST_P(MassFamilies, ConjugateGradientsMatchADenseSolveAndCorrectionsApproachIt)
{
  Scatter s(GetParam());
  const auto transfer                     = s.transfer();
  const NodalFields<2> &nodes             = transfer->nodes();
  const std::vector<unsigned int> &active = nodes.active;
  // A random right-hand side on the active fields, and its dense solution.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Tensor<1, 2>> rhs(nodes.mass.size()), lumped(nodes.mass.size());
  Tensor<1, 2> total;
  for (const unsigned int I : active)
  {
    rhs[I]    = Tensor<1, 2>({u(rng), u(rng)});
    lumped[I] = rhs[I] / nodes.mass[I];
    total += rhs[I];
  }
  // Fields lighter than a hundredth of a particle are held at their lumped values
  // (as a run holds those below its mass tolerance): with LME's far-reaching tails
  // they make M_C singular to round-off.
  const double light =
      1e-2 * *std::min_element(s.particles.mass.begin(), s.particles.mass.end());
  std::vector<unsigned int> free;
  for (const unsigned int I : active)
    if (nodes.mass[I] > light)
      free.push_back(I);
  const unsigned int n                 = free.size();
  const dealii::FullMatrix<double> all = dense_consistent_mass(*transfer, s.particles);
  dealii::FullMatrix<double> inverse(n, n);
  for (unsigned int i = 0; i < n; ++i)
    for (unsigned int j = 0; j < n; ++j)
      inverse(i, j) = all(free[i], free[j]);
  inverse.gauss_jordan();
  std::vector<Tensor<1, 2>> exact = lumped, b(n);
  for (unsigned int i = 0; i < n; ++i)
  {
    b[i] = rhs[free[i]];
    for (const unsigned int J : active)
      if (!(nodes.mass[J] > light))
        b[i] -= all(free[i], J) * lumped[J];
  }
  double size = 0;
  for (unsigned int i = 0; i < n; ++i)
  {
    exact[free[i]] = Tensor<1, 2>();
    for (unsigned int j = 0; j < n; ++j)
      exact[free[i]] += inverse(i, j) * b[j];
    size = std::max(size, exact[free[i]].norm());
  }

  RunParameters<2> run;
  run.consistent_mass            = true;
  run.consistent_mass_tolerance  = 1e-13;
  run.consistent_mass_iterations = 20000;
  MassSolve<2> solve(run);
  solve.assemble(*transfer, s.particles);
  const auto none             = [](std::vector<Tensor<1, 2>> &) {};
  std::vector<Tensor<1, 2>> x = lumped;
  solve.solve(*transfer, x, rhs, light, none, "test", 0);
  for (const unsigned int I : active)
    EXPECT_NEAR((x[I] - exact[I]).norm(), 0, 1e-10 * size) << "field " << I;
  std::map<std::string, double> results;
  solve.add_results(results);
  EXPECT_GT(results.at("mass_solve_max_iterations"), 2);
  std::cout << GetParam() << ": " << results.at("mass_solve_max_iterations")
            << " iterations" << std::endl;

  // A free body: the particles' momentum changes by sum_I m_I x_I, which equals the
  // total force to round-off (of that sum) even when the solve stops far from its
  // solution.
  run.consistent_mass_tolerance   = 1e-3;
  std::vector<Tensor<1, 2>> rough = lumped;
  solve.solve(*transfer, rough, rhs, light, none, "test", 0);
  Tensor<1, 2> momentum;
  double scale = 0;
  for (const unsigned int I : active)
    momentum += nodes.mass[I] * rough[I], scale += nodes.mass[I] * rough[I].norm();
  EXPECT_NEAR((momentum - total).norm(), 0, 1e-13 * scale);
  EXPECT_GT(lumped_norm(nodes, rough, exact), 100 * lumped_norm(nodes, x, exact));

  // Jacobi corrections: the error falls with each in the lumped-mass norm.
  std::vector<Tensor<1, 2>> corrected = lumped;
  double last                         = lumped_norm(nodes, corrected, exact);
  for (unsigned int k = 1; k <= 8; ++k)
  {
    transfer->correct_towards_consistent_mass(corrected, rhs, 1, light,
                                              [](std::vector<Tensor<1, 2>> &) {});
    const double error = lumped_norm(nodes, corrected, exact);
    EXPECT_LT(error, last) << "correction " << k;
    last = error;
  }
  EXPECT_GT(last, lumped_norm(nodes, x, exact));
}

INSTANTIATE_TEST_SUITE_P(ConsistentMass, MassFamilies,
                         ::testing::Values("linear", "ugimp", "bspline", "lme"),
                         [](const auto &info) { return info.param; });
