// CrackSet on its own: second fields across a crack, growing tips, bad input.
#include <deal.II/base/parameter_handler.h>

#include <lme_mpm/fracture/crack_set.h>

#include <gtest/gtest.h>

#include "test_helpers.h"

#include <fstream>
#include <numeric>

using namespace lme_mpm;

namespace
{
CrackSet<2> make_cracks(const std::string &polylines, const bool grow = true)
{
  ParameterHandler prm;
  CrackSet<2>::declare_parameters(prm);
  prm.enter_subsection("Cracks");
  prm.set("Polylines", polylines);
  prm.set("Grow with erosion", grow);
  prm.leave_subsection();
  CrackSet<2> cracks;
  cracks.parse_parameters(prm);
  return cracks;
}

void make_unit_grid(BackgroundGrid<2> &grid, const double h)
{
  const unsigned int n = std::lround(1 / h);
  grid.reinit(Point<2>(0, 0), {{std::vector<double>(n, h), std::vector<double>(n, h)}});
}

unsigned int node_at(const BackgroundGrid<2> &grid, const double x, const double y)
{
  std::array<unsigned int, 2> ijk;
  EXPECT_TRUE(grid.locate(Point<2>(x + 1e-9, y + 1e-9), ijk));
  return grid.node_index(ijk);
}
} // namespace

TEST(Cracks, PairsThatCrossTheCrackUseTheSecondField)
{
  // Crack from (0.2, 0.5) to (0.6, 0.5) on a grid of spacing 0.1: the node row y = 0.5
  // lies on the crack and belongs to the upper face.
  BackgroundGrid<2> grid;
  make_unit_grid(grid, 0.1);
  auto cracks = make_cracks("0.2, 0.5, 0.6, 0.5");
  FieldLayout layout;
  layout.reinit(grid.n_nodes());
  cracks.assign_fields(grid, 0.45, layout);
  const unsigned int on_line = node_at(grid, 0.4, 0.5), above = node_at(grid, 0.4, 0.6),
                     below = node_at(grid, 0.4, 0.4), past_tip = node_at(grid, 0.9, 0.6),
                     far = node_at(grid, 0.4, 0.0);
  for (const unsigned int I : {on_line, above, below, past_tip})
    ASSERT_NE(cracks.crack_node(I), numbers::invalid_unsigned_int);
  EXPECT_EQ(cracks.crack_node(far), numbers::invalid_unsigned_int);
  EXPECT_EQ(layout.n_extra(), cracks.n_crack_nodes());
  // The normal points from the node's side to the other face.
  EXPECT_LT(cracks.normal_of(cracks.crack_node(above))[1], -0.99);
  EXPECT_GT(cracks.normal_of(cracks.crack_node(below))[1], 0.99);

  ParticleStore<2> store;
  store.position = {Point<2>(0.4, 0.45), Point<2>(0.4, 0.55), Point<2>(0.75, 0.45)};
  store.body_id  = {0, 0, 0};
  Connectivity<2> conn;
  conn.resize(3, 4);
  const std::vector<unsigned int> nodes = {on_line, above, below, past_tip};
  for (unsigned int p = 0; p < 3; ++p)
  {
    conn.n_nodes[p] = 4;
    std::copy(nodes.begin(), nodes.end(), &conn.nodes[p * conn.stride]);
  }
  std::vector<std::uint8_t> touched(3, 7);
  cracks.separate(store, grid, conn, 0, 3, touched.data());
  EXPECT_EQ(touched, std::vector<std::uint8_t>(3, 1));
  const auto field = [&](const unsigned int p, const unsigned int k)
  {
    const unsigned int J = conn.nodes[p * conn.stride + k];
    return J < grid.n_nodes() ? 1 : 2;
  };
  // Below the crack: the nodes on and above it are across, the one below is not; the
  // line to the node past the tip crosses y = 0.5 on the crack too.
  EXPECT_EQ(field(0, 0), 2);
  EXPECT_EQ(field(0, 1), 2);
  EXPECT_EQ(field(0, 2), 1);
  EXPECT_EQ(field(0, 3), 2); // at x = 0.57
  // Above: only the node below is across.
  EXPECT_EQ(field(1, 0), 1);
  EXPECT_EQ(field(1, 1), 1);
  EXPECT_EQ(field(1, 2), 2);
  EXPECT_EQ(field(1, 3), 1);
  // Ahead of the tip the lines miss the crack (the ligament stays one body), except
  // the one to the node that lies on the crack and so belongs to its upper face.
  EXPECT_EQ(field(2, 0), 2);
  for (unsigned int k = 1; k < 4; ++k)
    EXPECT_EQ(field(2, k), 1) << "node " << k;
  EXPECT_EQ(conn.nodes[0], layout.find(on_line, FieldLayout::crack_side));
  EXPECT_EQ(conn.nodes[0], cracks.field_of(cracks.crack_node(on_line)));
  EXPECT_EQ(layout.node_of(conn.nodes[0]), on_line);
}

TEST(Cracks, TipsFollowTheFailedParticlesAhead)
{
  auto cracks = make_cracks("0, 0.5, 0.25, 0.5");
  ParticleStore<2> store;
  store.position = {Point<2>(0.27, 0.505), Point<2>(0.30, 0.495), Point<2>(0.29, 0.6),
                    Point<2>(0.20, 0.5),   Point<2>(0.45, 0.5),   Point<2>(0.33, 0.5),
                    Point<2>(0.28, 0.53)};
  store.failed   = {1, 1, 1, 1, 1, 0, 0};
  // Spacing 0.02: steps of 0.01 to 0.05 ahead, within 45 degrees of the tip's
  // direction, the most straight ahead first; (0.30, 0.495) is 0.0502 from the tip, so
  // it comes second.
  EXPECT_TRUE(cracks.grow(store, 0.02));
  const auto &line = cracks.polylines()[0];
  ASSERT_EQ(line.size(), 4u);
  EXPECT_EQ(line[1], Point<2>(0.25, 0.5));
  EXPECT_EQ(line[2], store.position[0]);
  EXPECT_EQ(line[3], store.position[1]);
  // Off to the side (0.29, 0.6), behind the tip (0.2), too far (0.45) and intact
  // (0.33) particles do not extend it; a second call finds nothing new.
  EXPECT_FALSE(cracks.grow(store, 0.02));

  auto fixed = make_cracks("0, 0.5, 0.25, 0.5", false);
  EXPECT_FALSE(fixed.grow(store, 0.02));

  // A failed particle with no intact one within reach has drifted out of the body.
  auto through = make_cracks("0, 0.5, 0.25, 0.5");
  ParticleStore<2> debris;
  debris.position = {Point<2>(0.27, 0.5), Point<2>(0.27, 0.56)};
  debris.failed   = {1, 0};
  EXPECT_FALSE(through.grow(debris, 0.02));
  debris.position[1] = Point<2>(0.27, 0.54);
  EXPECT_TRUE(through.grow(debris, 0.02));
}

TEST(Cracks, BodyOutOfRangeNamesTheEntry)
{
  ParameterHandler prm;
  CrackSet<2>::declare_parameters(prm);
  prm.enter_subsection("Cracks");
  prm.set("Polylines", "0, 0, 1, 1");
  prm.set("Body", "3");
  prm.leave_subsection();
  CrackSet<2> cracks;
  try
  {
    cracks.parse_parameters(prm, 2);
    FAIL() << "a crack in body 3 of 2 was accepted";
  }
  catch (const std::exception &e)
  {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("Cracks/Body"), std::string::npos) << msg;
    EXPECT_NE(msg.find("[1, 2]"), std::string::npos) << msg;
  }
}
