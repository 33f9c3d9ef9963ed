// NodeConstraints on their own: the node set from boundary ids and a box, the imposed
// components, the reaction M a - f and its impulse.
#include <gtest/gtest.h>

#include <lme_mpm/base/input.h>
#include <lme_mpm/boundary/node_constraints.h>

using namespace lme_mpm;

namespace
{
struct Sets
{
  BackgroundGrid<2> grid;
  dealii::ParameterHandler prm;
  NodeConstraints<2> constraints;

  explicit Sets(const std::vector<std::pair<std::string, std::string>> &entries)
  {
    grid.reinit(Point<2>(0, 0),
                {{std::vector<double>(4, 0.25), std::vector<double>(2, 0.5)}});
    NodeConstraints<2>::declare_parameters(prm, 1);
    prm.enter_subsection("Boundary conditions");
    prm.enter_subsection("Constraint 1");
    for (const auto &[key, value] : entries)
    {
      const auto path = input::split(key, '/');
      for (std::size_t i = 0; i + 1 < path.size(); ++i)
        prm.enter_subsection(path[i]);
      prm.set(path.back(), value);
      for (std::size_t i = 0; i + 1 < path.size(); ++i)
        prm.leave_subsection();
    }
    prm.leave_subsection();
    prm.leave_subsection();
    constraints.parse_parameters(prm, 1, grid);
  }
};
} // namespace

TEST(NodeConstraints, SetFromBoundaryIdsAndBoxImposesItsComponents)
{
  // The left face (x = 0: 3 nodes) and the node at (1, 0.5).
  Sets s({{"Name", "left"},
          {"Boundary ids", "0"},
          {"Box", "0.9, 0.4, 1.1, 0.6"},
          {"Components", "y"},
          {"Velocity/Function expression", "0; 2 * t"}});
  ASSERT_EQ(s.constraints.size(), 1u);
  const auto &set = s.constraints[0];
  EXPECT_EQ(set.name(), "left");
  EXPECT_EQ(set.nodes().size(), 4u);
  FieldLayout layout;
  layout.reinit(s.grid.n_nodes());
  std::vector<Tensor<1, 2>> x(s.grid.n_nodes(), Tensor<1, 2>({5, 5}));
  s.constraints.impose_rates(x, layout, 0.25);
  std::vector<Tensor<1, 2>> a(s.grid.n_nodes(), Tensor<1, 2>({5, 5}));
  s.constraints.impose_accelerations(a, layout, 0.25, 1e-3);
  for (unsigned int I = 0; I < s.grid.n_nodes(); ++I)
  {
    const bool in_set =
        std::find(set.nodes().begin(), set.nodes().end(), I) != set.nodes().end();
    EXPECT_EQ(x[I][0], 5.0); // x is free
    EXPECT_NEAR(x[I][1], in_set ? 0.5 : 5.0, 1e-14);
    EXPECT_NEAR(a[I][1], in_set ? 2.0 : 5.0, 1e-9);
  }
}

TEST(NodeConstraints, ReactionIsMassTimesAccelerationLessForce)
{
  Sets s({{"Name", "base"}, {"Boundary ids", "2"}, {"Components", "x, y"}});
  const auto &nodes = s.constraints[0].nodes();
  FieldLayout layout;
  layout.reinit(s.grid.n_nodes());
  const unsigned int n = s.grid.n_nodes();
  std::vector<double> mass(n, 2.0);
  std::vector<Tensor<1, 2>> acceleration(n), force(n), rate(n);
  for (unsigned int I = 0; I < n; ++I)
  {
    acceleration[I] = Tensor<1, 2>({0, 0});
    force[I]        = Tensor<1, 2>({1.0, -3.0});
  }
  const double dt   = 0.1;
  const double work = s.constraints.update_reactions(layout, mass, acceleration, force,
                                                     nullptr, rate, dt);
  // Held at rest: the constraint pushes back on every node's force, and does no work.
  const Tensor<1, 2> expected = -double(nodes.size()) * Tensor<1, 2>({1.0, -3.0});
  EXPECT_NEAR((s.constraints[0].reaction() - expected).norm(), 0, 1e-14);
  EXPECT_EQ(work, 0.0);
  // The impulse averages the reactions at the step's ends (0 before the first).
  EXPECT_NEAR((s.constraints[0].impulse() - 0.5 * dt * expected).norm(), 0, 1e-14);
}

TEST(NodeConstraints, EmptySetAndBadComponentNameTheirEntries)
{
  const auto error = [](const std::vector<std::pair<std::string, std::string>> &e)
  {
    try
    {
      Sets s(e);
    }
    catch (const std::exception &ex)
    {
      return input::concise_message(ex);
    }
    return std::string();
  };
  EXPECT_NE(error({{"Box", "5, 5, 6, 6"}}).find("Constraint 1"), std::string::npos);
  EXPECT_NE(error({{"Boundary ids", "0"}, {"Components", "z"}}).find("Components"),
            std::string::npos);
  EXPECT_NE(error({{"Boundary ids", "0"}, {"Name", "a b"}}).find("Name"),
            std::string::npos);
}
