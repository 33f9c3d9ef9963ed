// Shapes bounded by segments and triangles: polygons and regions read from mesh files
// cover the area or volume they enclose, holes included, and classify points at the
// mesh's own vertex coordinates consistently.
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_out.h>
#include <deal.II/grid/manifold_lib.h>
#include <deal.II/grid/tria.h>

#include <gtest/gtest.h>

#include <lme_mpm/base/input.h>
#include <lme_mpm/geometry/geometry.h>

#include "test_helpers.h"

#include <cmath>
#include <filesystem>
#include <fstream>

namespace
{
using namespace lme_mpm;

/// The area (2D) or volume (3D) of @p shape's points on an n^dim lattice of cell
/// midpoints over the box [lo, hi].
template <int dim>
double lattice_measure(const Geometry<dim> &shape, const Point<dim> &lo,
                       const Point<dim> &hi, const unsigned int n)
{
  double cell = 1;
  for (unsigned int d = 0; d < dim; ++d)
    cell *= (hi[d] - lo[d]) / n;
  std::size_t count = 0;
  std::array<unsigned int, dim> i{};
  while (true)
  {
    Point<dim> x;
    for (unsigned int d = 0; d < dim; ++d)
      x[d] = lo[d] + (i[d] + 0.5) * (hi[d] - lo[d]) / n;
    count += shape.inside(x);
    unsigned int d = 0;
    while (d < dim && ++i[d] == n)
      i[d] = 0, ++d;
    if (d == dim)
      break;
  }
  return count * cell;
}

/// Writes @p tria as a Gmsh file in the scratch directory; returns its path.
template <int dim>
std::string write_msh(const Triangulation<dim> &tria, const std::string &name)
{
  const std::string dir = lme_mpm_test::scratch("boundary_shapes");
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/" + name + ".msh";
  std::ofstream out(path);
  GridOut().write_msh(tria, out);
  return path;
}

template <int dim>
double mesh_measure(const Triangulation<dim> &tria)
{
  double m = 0;
  for (const auto &cell : tria.active_cell_iterators())
    m += cell->measure();
  return m;
}
} // namespace

TEST(BoundaryShapes, PolygonCoversItsAreaAndMatchesTheRectangle)
{
  const auto &shapes = GeometryRegistry<2>::instance();
  // An L of area 0.75 in the unit square, vertices on the lattice's cell faces.
  const auto l_shape = shapes.create(
      "polygon(0, 0, 1, 0, 1, 0.5, 0.5, 0.5, 0.5, 1, 0, 1)", "Body 1/Shape");
  EXPECT_NEAR(lattice_measure<2>(*l_shape, Point<2>(0, 0), Point<2>(1, 1), 400), 0.75,
              1e-12);
  // Points on the lattice of the vertices: inside on the left and bottom edges.
  EXPECT_TRUE(l_shape->inside(Point<2>(0.25, 0.25)));
  EXPECT_FALSE(l_shape->inside(Point<2>(0.75, 0.75)));
  EXPECT_FALSE(l_shape->inside(Point<2>(1.5, 0.25)));

  // The signed distance and normal of a square polygon are the rectangle's.
  const auto square =
      shapes.create("polygon(0.2, 0.1, 0.6, 0.1, 0.6, 0.3, 0.2, 0.3)", "Body 1/Shape");
  const auto box = shapes.create("rectangle(0.2, 0.1, 0.6, 0.3)", "Body 1/Shape");
  for (const Point<2> &x : {Point<2>(0.3, 0.15), Point<2>(0.9, 0.5), Point<2>(0.4, -0.2),
                            Point<2>(0.1, 0.2), Point<2>(0.59, 0.2)})
  {
    double d_polygon = 0, d_box = 0;
    Tensor<1, 2> n_polygon, n_box;
    ASSERT_TRUE(square->signed_distance(x, d_polygon, n_polygon));
    ASSERT_TRUE(box->signed_distance(x, d_box, n_box));
    EXPECT_NEAR(d_polygon, d_box, 1e-14) << x;
    // Outside a corner the box's normal points from the corner; so does the polygon's.
    EXPECT_NEAR((n_polygon - n_box).norm(), 0, 1e-12) << x;
  }

  // Input the registry refuses, naming the entry.
  for (const char *bad : {"polygon(0, 0, 1, 0)", "polygon(0, 0, 1, 0, 1)",
                          "polygon(0, 0, 1, 0, 1, 0, 0, 1)", "polygon(0, 0, 1, 1, 2, 2)"})
  {
    std::string message;
    try
    {
      shapes.create(bad, "Body 1/Shape");
    }
    catch (const std::exception &e)
    {
      message = input::concise_message(e);
    }
    EXPECT_NE(message.find("Body 1/Shape"), std::string::npos) << bad;
    EXPECT_NE(message.find("polygon"), std::string::npos) << bad << ": " << message;
  }
}

TEST(BoundaryShapes, GmshDiscInMillimetresHasTheDiscsArea)
{
  // prm/meshes/disc_100mm.msh: Gmsh 4.1, triangles of 4 mm, a disc of radius 50 mm.
  const std::string file = std::string(LME_MPM_SOURCE_DIR) + "/prm/meshes/disc_100mm.msh";
  const auto disc =
      GeometryRegistry<2>::instance().create("mesh(" + file + ", 0.001)", "Body 1/Shape");
  const auto box = disc->bounding_box().get_boundary_points();
  // In metres; the polygon's vertices lie on the circle, within a sagitta (0.04 mm)
  // of its extreme points.
  EXPECT_NEAR(box.first[0], 0.05, 1e-4);
  EXPECT_NEAR(box.second[1], 0.15, 1e-4);
  const double area =
      lattice_measure<2>(*disc, Point<2>(0.04, 0.04), Point<2>(0.16, 0.16), 1200);
  // The inscribed polygon of ~79 sides loses 0.1 % of the disc; the lattice adds
  // about 0.05 %.
  EXPECT_NEAR(area / (M_PI * 0.05 * 0.05), 1.0, 3e-3);
}

TEST(BoundaryShapes, MeshRegionsWithHolesAndIn3D)
{
  // A 2D annulus: the inner boundary is a hole by the even-odd rule.
  {
    Triangulation<2> tria;
    GridGenerator::hyper_shell(tria, Point<2>(0.5, 0.5), 0.1, 0.3, 16);
    tria.refine_global(3);
    const auto ring = GeometryRegistry<2>::instance().create(
        "mesh(" + write_msh(tria, "ring") + ")", "Body 1/Shape");
    EXPECT_FALSE(ring->inside(Point<2>(0.5, 0.5)));
    EXPECT_TRUE(ring->inside(Point<2>(0.7, 0.5)));
    const double area =
        lattice_measure<2>(*ring, Point<2>(0.1, 0.1), Point<2>(0.9, 0.9), 1000);
    EXPECT_NEAR(area / mesh_measure(tria), 1.0, 2e-3);
  }
  // A 3D ball of hexahedra: its boundary quads split into triangles.
  {
    Triangulation<3> tria;
    GridGenerator::hyper_ball(tria, Point<3>(0.5, 0.5, 0.5), 0.4);
    tria.refine_global(2);
    const auto ball = GeometryRegistry<3>::instance().create(
        "mesh(" + write_msh(tria, "ball") + ")", "Body 1/Shape");
    const double volume =
        lattice_measure<3>(*ball, Point<3>(0, 0, 0), Point<3>(1, 1, 1), 120);
    EXPECT_NEAR(volume / mesh_measure(tria), 1.0, 1e-2);
  }
  // A 3D box of 4^3 hexahedra, sampled on a lattice through its vertices' coordinates:
  // rays through shared edges and vertices count once.
  {
    Triangulation<3> tria;
    GridGenerator::subdivided_hyper_rectangle(tria, {4, 4, 4}, Point<3>(0.25, 0.25, 0.25),
                                              Point<3>(0.75, 0.75, 0.75));
    const auto box = GeometryRegistry<3>::instance().create(
        "mesh(" + write_msh(tria, "box") + ")", "Body 1/Shape");
    std::size_t wrong = 0;
    for (unsigned int i = 0; i <= 16; ++i)
      for (unsigned int j = 0; j <= 16; ++j)
        for (unsigned int k = 0; k <= 16; ++k)
        {
          // Lattice points at 1/16 steps: the faces at 0.25, 0.75 and every mesh
          // vertex's coordinates among them; strictly interior ones must be inside.
          const Point<3> x(i / 16.0, j / 16.0, k / 16.0);
          bool interior = true, exterior = false;
          for (unsigned int d = 0; d < 3; ++d)
            interior = interior && x[d] > 0.25 && x[d] < 0.75,
            exterior = exterior || x[d] < 0.25 || x[d] > 0.75;
          if ((interior && !box->inside(x)) || (exterior && box->inside(x)))
            ++wrong;
        }
    EXPECT_EQ(wrong, 0u);
  }
}

TEST(BoundaryShapes, BadMeshInputNamesTheEntry)
{
  const auto message = [](const std::string &text)
  {
    try
    {
      GeometryRegistry<2>::instance().create(text, "Body 1/Holes");
    }
    catch (const std::exception &e)
    {
      return input::concise_message(e);
    }
    return std::string();
  };
  EXPECT_NE(message("mesh(no_such_file.msh)")
                .find("cannot open the mesh file "
                      "'no_such_file.msh'"),
            std::string::npos);
  EXPECT_NE(message("mesh(disc.stl)").find("cannot tell the format"), std::string::npos);
  EXPECT_NE(message("mesh(disc.msh, gltf)").find("unknown mesh format 'gltf'"),
            std::string::npos);
  EXPECT_NE(message("mesh(disc.msh, -2)").find("must be positive"), std::string::npos);
  // A file that is not a mesh of the format its extension names.
  const std::string dir = lme_mpm_test::scratch("bad_mesh");
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/junk.msh") << "this is not a mesh\n";
  const std::string junk = message("mesh(" + dir + "/junk.msh)");
  EXPECT_NE(junk.find("Body 1/Holes"), std::string::npos) << junk;
  EXPECT_NE(junk.find("cannot read the mesh file"), std::string::npos) << junk;
}

TEST(BoundaryShapes, TurnedBoxInItsOwnAxes)
{
  // A 60 x 10 x 4 box turned by 30 degrees about z and tilted 35 degrees towards +z:
  // points along its own axes are inside up to the half sides and outside beyond; its
  // bounding box holds its corners; the signed distance is the axis-aligned box's in
  // the box's own frame.
  const double a = 30 * M_PI / 180, b = 35 * M_PI / 180;
  const Tensor<1, 3> t(
      {std::cos(b) * std::cos(a), std::cos(b) * std::sin(a), std::sin(b)}),
      w({-std::sin(a), std::cos(a), 0}), n = cross_product_3d(t, w);
  const Point<3> c(0.1, 0.2, 0.3);
  const auto box = GeometryRegistry<3>::instance().create(
      "turned_box(0.1, 0.2, 0.3, 0.06, 0.01, 0.004, 30, 35)", "test");
  for (const auto &[axis, half] :
       {std::pair{t, 0.03}, std::pair{w, 0.005}, std::pair{n, 0.002}})
    for (const double sign : {-1.0, 1.0})
    {
      EXPECT_TRUE(box->inside(c + 0.99 * sign * half * axis));
      EXPECT_FALSE(box->inside(c + 1.01 * sign * half * axis));
      double distance;
      Tensor<1, 3> normal;
      ASSERT_TRUE(
          box->signed_distance(c + (half + 0.001) * sign * axis, distance, normal));
      EXPECT_NEAR(distance, 0.001, 1e-12);
      EXPECT_NEAR((normal - sign * axis).norm(), 0, 1e-12);
    }
  double distance;
  Tensor<1, 3> normal;
  ASSERT_TRUE(box->signed_distance(c, distance, normal));
  EXPECT_NEAR(distance, -0.002, 1e-12);
  const BoundingBox<3> bounds = box->bounding_box();
  for (const double s : {-0.03, 0.03})
    for (const double u : {-0.005, 0.005})
      for (const double v : {-0.002, 0.002})
      {
        const Point<3> corner = c + s * t + u * w + v * n;
        EXPECT_TRUE(bounds.point_inside(corner, 1e-12));
        for (unsigned int d = 0; d < 3; ++d)
          EXPECT_GE(bounds.side_length(d), 0);
      }
  // In 2D the same rectangle as a slot from its lower end.
  const auto turned = GeometryRegistry<2>::instance().create(
      "turned_box(0.1, 0.2, 0.06, 0.01, 30)", "test");
  const auto slot = GeometryRegistry<2>::instance().create(
      "slot(" + std::to_string(0.1 - 0.03 * std::cos(a)) + ", " +
          std::to_string(0.2 - 0.03 * std::sin(a)) + ", 0.06, 0.01, 30)",
      "test");
  unsigned int same = 0, inside = 0;
  for (unsigned int i = 0; i < 100; ++i)
    for (unsigned int j = 0; j < 100; ++j)
    {
      const Point<2> x(0.06 + 0.0008 * i, 0.16 + 0.0008 * j);
      same += turned->inside(x) == slot->inside(x);
      inside += turned->inside(x);
    }
  EXPECT_GE(same, 9990u);
  EXPECT_GT(inside, 700u);
}
