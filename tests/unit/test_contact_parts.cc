// The parts of contact on their own: fields per body at shared nodes, the nodal
// exchange between pairs (momentum kept, approach removed), and the force means the
// output reads.
#include <gtest/gtest.h>

#include <lme_mpm/contact/body_contact.h>
#include <lme_mpm/geometry/particle_generator.h>
#include <lme_mpm/output/force_means.h>
#include <lme_mpm/output/moving_mean.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

using namespace lme_mpm;

namespace
{
/// Two blocks of particles, one cell apart, moving towards each other along x.
struct TwoBlocks
{
  BackgroundGrid<2> grid;
  ParticleStore<2> particles;
  Bodies<2> bodies;
  std::unique_ptr<ShapeFunction<2>> functions;
  std::unique_ptr<GridTransfer<2>> transfer;
  std::unique_ptr<BodyContact<2>> contact;

  explicit TwoBlocks(const std::string &exchange, const std::string &sweeps = "8",
                     const std::string &tolerance = "1e-4")
  {
    grid.reinit(Point<2>(0, 0),
                {{std::vector<double>(10, 0.1), std::vector<double>(6, 0.1)}});
    for (const int body : {0, 1})
      for (unsigned int i = 0; i < 6; ++i)
        for (unsigned int j = 0; j < 4; ++j)
        {
          const double x0 = body == 0 ? 0.2 : 0.5;
          const std::size_t p =
              particles.add(Point<2>(x0 + 0.05 * i + 0.025, 0.2 + 0.05 * j + 0.025),
                            body == 0 ? 1.0 : 3.0, 2.5e-3, 0, body);
          particles.velocity[p] = Tensor<1, 2>({body == 0 ? 1.0 : -0.5, 0.1 * body});
        }
    for (std::size_t p = 0; p < particles.size(); ++p)
      particles.id[p] = p;
    dealii::ParameterHandler prm;
    // As the run declares them: the shape's entries (Surface among them) and the rules.
    ParticleGenerator<2>::declare_parameters(prm, 2);
    Bodies<2>::declare_parameters(prm, 2);
    BodyContact<2>::declare_parameters(prm);
    ShapeFunctionRegistry<2>::instance().declare_all(prm);
    prm.enter_subsection("Contact");
    prm.set("Type", "multi-field");
    prm.set("Exchange", exchange);
    prm.set("Contact volume fraction", "0.1");
    prm.set("Exchange sweeps", sweeps);
    prm.set("Exchange tolerance", tolerance);
    prm.leave_subsection();
    bodies.parse_parameters(prm, 2, {});
    ShapeFunctionContext<2> context;
    context.grid = &grid;
    functions    = ShapeFunctionRegistry<2>::instance().create("linear", prm, context);
    transfer     = std::make_unique<GridTransfer<2>>(grid, particles);
    contact      = std::make_unique<BodyContact<2>>(grid, *transfer, particles, bodies);
    contact->parse_parameters(prm, 1.0, functions->support_radius(grid));
    transfer->nodes().layout.reinit(grid.n_nodes());
    EXPECT_EQ(transfer->locate_and_sort(), particles.size());
    contact->assign_fields(particles, transfer->nodes().layout);
    transfer->particles_to_grid(*functions, {},
                                [&](const std::size_t b, const std::size_t e)
                                { contact->separate(transfer->connectivity(), b, e); });
  }

  /// Half the rates' mass-weighted squares, summed over the fields.
  double kinetic_energy() const
  {
    double e = 0;
    for (const unsigned int F : transfer->nodes().active)
      e += 0.5 * transfer->nodes().mass[F] * transfer->nodes().rate[F].norm_square();
    return e;
  }
  Tensor<1, 2> nodal_momentum() const
  {
    Tensor<1, 2> m;
    for (const unsigned int F : transfer->nodes().active)
      m += transfer->nodes().mass[F] * transfer->nodes().rate[F];
    return m;
  }
};
} // namespace

TEST(BodyFields, SharedNodesGetAFieldPerBodyAndPairsFollowTheirBody)
{
  TwoBlocks s("nodal");
  const BodyFields<2> &fields = s.contact->body_fields();
  ASSERT_TRUE(fields.active());
  ASSERT_FALSE(fields.shared_nodes().empty());
  const FieldLayout &layout = s.transfer->nodes().layout;
  for (const unsigned int I : fields.shared_nodes())
  {
    EXPECT_EQ(fields.field_of_body(I, 0), I); // the lowest body keeps the node's own
    const unsigned int F = fields.field_of_body(I, 1);
    ASSERT_NE(F, FieldLayout::invalid);
    EXPECT_NE(F, I);
    EXPECT_EQ(layout.node_of(F), I);
  }
  // Every particle-node pair goes to a field of the particle's own body.
  const Connectivity<2> &conn = s.transfer->connectivity();
  for (std::size_t p = 0; p < s.particles.size(); ++p)
    for (unsigned int k = 0; k < conn.n_nodes[p]; ++k)
    {
      const unsigned int F = conn.nodes[p * conn.stride + k];
      const unsigned int I = layout.node_of(F);
      EXPECT_EQ(fields.field_of_body(I, s.particles.body_id[p]), F);
    }
}

// The marks are kept while no particle changes cell, and follow one that does.
TEST(BodyFields, MarksStandWhileNoParticleChangesCellAndFollowOneThatDoes)
{
  TwoBlocks s("nodal");
  const BodyFields<2> &fields                 = s.contact->body_fields();
  FieldLayout &layout                         = s.transfer->nodes().layout;
  const std::vector<unsigned int> shared_then = fields.shared_nodes();
  ASSERT_FALSE(shared_then.empty());
  s.contact->assign_fields(s.particles, layout);
  EXPECT_EQ(fields.shared_nodes(), shared_then);
  // A particle of body 1 (the block at x >= 0.5) moved to the cell left of body 0's
  // block: the nodes at x = 0.1 and 0.2 near it now hold both bodies.
  std::size_t moved = 0;
  while (s.particles.body_id[moved] != 1)
    ++moved;
  s.particles.position[moved] = Point<2>(0.05, 0.325);
  ASSERT_EQ(s.transfer->locate_and_sort(), s.particles.size());
  s.contact->assign_fields(s.particles, layout);
  const unsigned int node = s.grid.node_index({{1, 3}}); // (0.1, 0.3)
  const auto &shared_now  = fields.shared_nodes();
  EXPECT_EQ(std::count(shared_then.begin(), shared_then.end(), node), 0);
  EXPECT_EQ(std::count(shared_now.begin(), shared_now.end(), node), 1);
  EXPECT_NE(fields.field_of_body(node, 1), FieldLayout::invalid);
}

TEST(ContactPairs, NodalExchangeKeepsMomentumAndStopsEveryApproach)
{
  TwoBlocks s("nodal");
  ExplicitNewmark newmark;
  s.transfer->predict_rates(newmark, 0, 1e-20);
  ContactPairs<2> pairs;
  pairs.set_up(s.grid, "larger volume", 0.1, 0.0, "", 2, 1.0);
  pairs.find(s.contact->body_fields(), s.bodies, *s.transfer, s.particles, 1e-20);
  ASSERT_FALSE(pairs.empty());
  auto &rate                 = s.transfer->nodes().rate;
  const auto &mass           = s.transfer->nodes().mass;
  const Tensor<1, 2> before  = s.nodal_momentum();
  const double energy_before = s.kinetic_energy();
  unsigned int approaching   = 0;
  for (const auto &q : pairs.list())
    approaching += (rate[q.a] - rate[q.b]) * q.normal > 0;
  EXPECT_GT(approaching, 0u);
  pairs.exchange(
      rate, mass, [&](const unsigned int F) { return rate[F]; }, 1.0, true, s.bodies,
      [](const auto &, const Tensor<1, 2> &, bool) {});
  for (const auto &q : pairs.list())
  {
    // Normals are unit vectors from a to b; frictionless: only the normal part moves.
    EXPECT_NEAR(q.normal.norm(), 1.0, 1e-14);
    EXPECT_LE((rate[q.a] - rate[q.b]) * q.normal, 1e-12);
  }
  EXPECT_NEAR((s.nodal_momentum() - before).norm(), 0, 1e-12 * before.norm());
  // The exchange is inelastic: the rates' kinetic energy does not grow.
  EXPECT_LT(s.kinetic_energy(), energy_before);
}

TEST(BodyContact, ProjectedExchangeKeepsParticleMomentum)
{
  TwoBlocks s("projected");
  ExplicitNewmark newmark;
  s.transfer->predict_rates(newmark, 0, 1e-20);
  Tensor<1, 2> before, after;
  for (std::size_t p = 0; p < s.particles.size(); ++p)
    before += s.particles.mass[p] * s.particles.velocity[p];
  s.contact->on_rates(1e-20, 1e-4);
  ASSERT_GT(s.contact->n_contact_pairs(), 0u);
  for (std::size_t p = 0; p < s.particles.size(); ++p)
    after += s.particles.mass[p] * s.particles.velocity[p];
  EXPECT_NEAR((after - before).norm(), 0, 1e-12 * before.norm());
  // Equal and opposite forces on the two bodies.
  const auto &f = s.contact->step_forces();
  EXPECT_NEAR((f[0] + f[1]).norm(), 0, 1e-9 * f[0].norm());
  EXPECT_LT(f[0][0], 0); // the left block is pushed back
}

TEST(BodyContact, ProjectedExchangeSweepsUntilTheRatesStopApproaching)
{
  // The largest approach of a pair's projected rates, after one exchange, relative to
  // the largest before it: one sweep leaves some (the iteration is under-relaxed where
  // the contact varies from node to node), sweeps to a tight tolerance remove it.
  const auto exchange = [](const std::string &sweeps, const std::string &tolerance,
                           const unsigned int calls, std::map<std::string, double> &r)
  {
    TwoBlocks s("projected", sweeps, tolerance);
    ExplicitNewmark newmark;
    s.transfer->predict_rates(newmark, 0, 1e-20);
    ContactPairs<2> pairs;
    pairs.set_up(s.grid, "larger volume", 0.1, 0.0, "", 2, 1.0);
    pairs.find(s.contact->body_fields(), s.bodies, *s.transfer, s.particles, 1e-20);
    const auto &rate    = s.transfer->nodes().rate;
    const auto approach = [&]()
    {
      double worst = 0;
      for (const auto &q : pairs.list())
        worst = std::max(worst, (rate[q.a] - rate[q.b]) * q.normal);
      return worst;
    };
    const double before = approach();
    EXPECT_GT(before, 0.5);
    // A second exchange on rates that no longer approach starts from the first one's
    // impulses, which it must take back.
    for (unsigned int c = 0; c < calls; ++c)
      s.contact->on_rates(1e-20, 1e-4);
    s.contact->add_results(r);
    return approach() / before;
  };
  std::map<std::string, double> one, tight, again;
  const double after_one   = exchange("1", "0", 1, one);
  const double after_tight = exchange("1000", "1e-10", 1, tight);
  const double after_again = exchange("1000", "1e-10", 2, again);
  std::cout << "approach left: one sweep " << after_one << ", to 1e-10 " << after_tight
            << " (" << tight.at("contact_max_exchange_sweeps") << " sweeps), again "
            << after_again << std::endl;
  EXPECT_EQ(one.at("contact_max_exchange_sweeps"), 1);
  EXPECT_GT(after_one, 1e-3);
  EXPECT_LT(after_tight, 1e-8);
  EXPECT_GT(tight.at("contact_max_exchange_sweeps"), 1);
  EXPECT_LT(tight.at("contact_max_exchange_sweeps"), 1000);
  EXPECT_LT(after_again, 1e-8);
}

TEST(ForceMeans, RowMeanIsTheImpulseOverTheIntervalAndTheWindowMeanIsTrackedEveryStep)
{
  ForceMeans<2> means;
  means.reset(2, 0.35); // a window of 0.35 s
  const std::vector<Tensor<1, 2>> a = {Tensor<1, 2>({2, 0}), Tensor<1, 2>({-2, 0})};
  const std::vector<Tensor<1, 2>> b = {Tensor<1, 2>({4, 0}), Tensor<1, 2>({-4, 0})};
  // A first row with no step behind it reports the step's force.
  means.close_row(a);
  EXPECT_EQ(means.mean()[0][0], 2.0);
  means.book(a, 0.1);
  // The window reaches back before the first step, where nothing acted.
  EXPECT_NEAR(means.current()[0][0], 2.0 * 0.1 / 0.35, 1e-14);
  means.book(b, 0.3); // the window now spans both steps (0.4 s >= 0.35 s)
  EXPECT_NEAR(means.current()[0][0], (0.2 + 1.2) / 0.4, 1e-14);
  means.close_row(b);
  EXPECT_NEAR(means.mean()[0][0], (0.2 + 1.2) / 0.4, 1e-14);
  means.book(b, 0.1); // the first step drops out: 0.4 s of b alone
  EXPECT_NEAR(means.current()[1][0], -4.0, 1e-14);
  EXPECT_NEAR(means.peak()[1], 4.0, 1e-14);
  means.book(a, 0.1);
  means.close_row(a);
  EXPECT_NEAR(means.mean()[0][0], 3.0, 1e-14); // the row's interval: 0.1 b, 0.1 a
  EXPECT_NEAR(means.current()[0][0], (0.4 * 4 + 0.1 * 2) / 0.5, 1e-14);
  EXPECT_NEAR(means.peak()[0], 4.0, 1e-14); // the peak stays
}

TEST(MovingMean, WindowOfZeroKeepsTheLastStepAndRestoresExactly)
{
  MovingMean last;
  last.reset(1, 0);
  for (const double v : {1.0, 5.0, -2.0})
  {
    last.book(&v, 1e-3);
    EXPECT_EQ(last.mean(0), v);
  }
  // A long window over many steps: the mean is summed afresh each step, and a copy
  // through an archive goes on with the same bits.
  MovingMean long_window, copy;
  long_window.reset(2, 1e-3);
  std::stringstream bytes;
  for (int step = 0; step < 1000; ++step)
  {
    const std::vector<double> v = {std::sin(0.1 * step), double(step)};
    long_window.book(v, 7e-5);
    if (step == 500)
    {
      Archive out(static_cast<std::ostream &>(bytes));
      long_window.serialize(out);
      Archive in(static_cast<std::istream &>(bytes));
      copy.serialize(in);
    }
    if (step > 500)
      copy.book(v, 7e-5);
  }
  EXPECT_EQ(copy.mean(0), long_window.mean(0));
  EXPECT_EQ(copy.mean(1), long_window.mean(1));
  // 15 steps of 7e-5 s span the 1e-3 s window: the mean of steps 985 to 999.
  EXPECT_NEAR(long_window.mean(1), 992.0, 1e-9);
}
