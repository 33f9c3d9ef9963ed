// Unit tests particular to the uGIMP and cubic B-spline shape functions.

#include "shape_function_checks.h"

#include <lme_mpm/shape_functions/tensor_product.h>

#include <type_traits>

using namespace lme_mpm;
using namespace shape_function_checks;

TEST(ShapeFunctions, UgimpIsTheAverageOfTheHatFunctions)
{
  // Independent check: average the Q1 hats over the particle box with the trapezoidal
  // rule on the pieces between grid lines (exact for piecewise-linear integrands).
  const auto hat = [](const std::vector<double> &c, const unsigned int I, const double s)
  {
    if (I > 0 && s >= c[I - 1] && s <= c[I])
      return (s - c[I - 1]) / (c[I] - c[I - 1]);
    if (I + 1 < c.size() && s >= c[I] && s <= c[I + 1])
      return (c[I + 1] - s) / (c[I + 1] - c[I]);
    return 0.0;
  };
  const auto average =
      [&](const std::vector<double> &c, const unsigned int I, double a, double b)
  {
    std::vector<double> cuts = {a, b};
    for (const double ci : c)
      if (ci > a && ci < b)
        cuts.push_back(ci);
    std::sort(cuts.begin(), cuts.end());
    double sum = 0;
    for (unsigned int k = 0; k + 1 < cuts.size(); ++k)
      sum +=
          0.5 * (cuts[k + 1] - cuts[k]) * (hat(c, I, cuts[k]) + hat(c, I, cuts[k + 1]));
    return sum / (b - a);
  };
  for (const bool graded : {false, true})
  {
    auto grid              = graded ? graded_grid<2>() : uniform_grid<2>(0.1, 8);
    const double thickness = 0.01;
    auto sf                = make<2>("ugimp", *grid, {}, thickness);
    std::mt19937 rng(61);
    ParticleStore<2> ps;
    const double lp = 0.3 * grid->min_spacing();
    for (unsigned int i = 0; i < 50; ++i)
      ps.add(random_point(*grid, rng, lp), 1.0, volume_for_half_width<2>(lp, thickness),
             0, 0);
    const auto conn = evaluate(*sf, ps);
    for (std::size_t p = 0; p < ps.size(); ++p)
    {
      const Point<2> &x = ps.position[p];
      double total      = 0;
      for (unsigned int k = 0; k < conn.n_nodes[p]; ++k)
      {
        const unsigned int node = conn.nodes[p * conn.stride + k];
        const unsigned int i    = node % grid->n_nodes_in(0);
        const unsigned int j    = node / grid->n_nodes_in(0);
        const double expected   = average(grid->coordinates(0), i, x[0] - lp, x[0] + lp) *
                                average(grid->coordinates(1), j, x[1] - lp, x[1] + lp);
        EXPECT_NEAR(conn.N[p * conn.stride + k], expected, 1e-14);
        total += expected;
      }
      EXPECT_NEAR(total, 1.0, 1e-13); // no node with weight was left out
    }
  }
}

TEST(ShapeFunctions, UgimpDomainIsClippedAtTheGridEdge)
{
  const double h = 0.1;
  auto grid      = uniform_grid<2>(h, 6);
  auto sf        = make<2>("ugimp", *grid);
  {
    // Box [x - 0.25 h, x + 0.25 h] sticks out of the lower face by 0.05 h: clipped,
    // so the weights are those of the box [x0, x + 0.25 h] and still sum to one.
    ParticleStore<2> ps;
    const Point<2> x = grid->lower_corner() + Point<2>(0.2 * h, 0.3);
    ps.add(x, 1.0, volume_for_half_width<2>(0.25 * h), 0, 0);
    Connectivity<2> conn;
    conn.resize(1, sf->max_nodes_per_particle());
    sf->compute(*&ps, 0, 1, conn);
    double sum = 0;
    Point<2> centre;
    for (unsigned int k = 0; k < conn.n_nodes[0]; ++k)
    {
      sum += conn.N[k];
      centre += conn.N[k] * grid->node_point(conn.nodes[k]);
    }
    EXPECT_NEAR(sum, 1.0, 1e-14);
    const double clipped_centre = grid->lower_corner()[0] + 0.5 * (0.2 + 0.25) * h;
    EXPECT_NEAR(centre[0], clipped_centre, 1e-12);
    EXPECT_NEAR(centre[1], x[1], 1e-12);
  }
  // A particle whose centre is outside the grid is an error.
  expect_failure<2>(*sf, grid->lower_corner() + Point<2>(-0.01 * h, 0.3),
                    volume_for_half_width<2>(0.25 * h));
  // A box wider than a cell would need more nodes than the bound.
  expect_failure<2>(*sf, cell_centre<2>(*grid, {{2, 2}}) + Point<2>(0.3 * h, 0),
                    volume_for_half_width<2>(0.75 * h));
  expect_failure<2>(*sf, cell_centre<2>(*grid, {{2, 2}}), 0.0);
}

TEST(ShapeFunctions, BsplineNeedsAUniformGrid)
{
  auto graded = graded_grid<2>();
  try
  {
    make<2>("bspline", *graded);
    ADD_FAILURE() << "no exception";
  }
  catch (const ExceptionBase &e)
  {
    EXPECT_NE(std::string(e.what()).find("Shape functions/Type"), std::string::npos)
        << e.what();
  }
  EXPECT_ANY_THROW(make<3>("bspline", *graded_grid<3>()));
  EXPECT_NO_THROW(make<2>("bspline", *uniform_grid<2>(0.1, 4)));
}

TEST(ShapeFunctions, RowsKeptAsFactorsVisitTheFullRowsNodesAndValues)
{
  // Every tensor-product family in 2D and 3D, on uniform and graded grids: the rows
  // compute() keeps as factors (linear: also as the cells alone) give, node by node,
  // the index, value and gradient of the row it writes in full, to the bit (the
  // transfers read either).
  const auto check = [](auto dim_tag, const std::string &type, const bool graded,
                        const bool from_cells = false)
  {
    constexpr int dim      = decltype(dim_tag)::value;
    auto grid              = graded ? graded_grid<dim>() : uniform_grid<dim>(0.1, 6);
    const double thickness = 0.01;
    auto sf                = make<dim>(type, *grid, {}, thickness);
    std::mt19937 rng(7);
    ParticleStore<dim> ps;
    const double lp = 0.3 * grid->min_spacing();
    for (unsigned int i = 0; i < 200; ++i)
      ps.add(random_point(*grid, rng, 0.5 * lp), 1.0,
             volume_for_half_width<dim>(lp, thickness), 0, 0);
    const Connectivity<dim> full = evaluate(*sf, ps);
    // Linear rows have at most 2 nodes per direction, the others 4.
    const unsigned int width = type == "linear" ? 2 : 4;
    Connectivity<dim> factors;
    if (from_cells)
      factors.resize_cells(ps.size(), ps.position);
    else
      factors.resize_factors(ps.size(), width);
    sf->compute(ps, 0, ps.size(), factors);
    EXPECT_TRUE(factors.nodes.empty() && factors.n_nodes.empty());
    EXPECT_EQ(factors.cells.empty(), !from_cells);
    std::size_t checked = 0, differ = 0;
    with_rows(*grid, factors,
              [&](const auto &rows)
              {
                for (std::size_t p = 0; p < ps.size(); ++p)
                {
                  unsigned int k = 0;
                  rows.visit(
                      p,
                      [&](const unsigned int I, const double N, const Tensor<1, dim> &g)
                      {
                        const std::size_t o = p * full.stride + k;
                        differ +=
                            I != full.nodes[o] || N != full.N[o] || g != full.grad_N[o];
                        ++k, ++checked;
                      });
                  EXPECT_EQ(k, full.n_nodes[p]);
                  const auto [first, last] = rows.first_and_last(p);
                  EXPECT_EQ(first, full.nodes[p * full.stride]);
                  EXPECT_EQ(last, full.nodes[p * full.stride + full.n_nodes[p] - 1]);
                }
              });
    EXPECT_GT(checked, ps.size()) << type;
    EXPECT_EQ(differ, 0u) << type << " in " << dim << "D"
                          << (from_cells ? ", rows formed from the cells" : "");
  };
  for (const bool graded : {false, true})
  {
    for (const bool from_cells : {false, true})
    {
      check(std::integral_constant<int, 2>(), "linear", graded, from_cells);
      check(std::integral_constant<int, 3>(), "linear", graded, from_cells);
    }
    check(std::integral_constant<int, 2>(), "ugimp", graded);
    check(std::integral_constant<int, 3>(), "ugimp", graded);
  }
  check(std::integral_constant<int, 2>(), "bspline", false);
  check(std::integral_constant<int, 3>(), "bspline", false);
}
