#ifndef LME_MPM_GEOMETRY_BOUNDARY_SHAPES_H
#define LME_MPM_GEOMETRY_BOUNDARY_SHAPES_H

#include <lme_mpm/geometry/geometry.h>

#include <array>
#include <string>
#include <vector>

namespace lme_mpm
{
/**
 * Closed loops of straight segments in the x-y plane: a polygon's edges or a 2D mesh's
 * boundary. A point is inside by the even-odd rule, so that a loop inside another is
 * a hole, whatever the loops' orientation. Segments are binned in strips of y, so a
 * query costs the segments of one strip (a few for a mesh's boundary), not all.
 */
class SegmentBoundary
{
public:
  using Segment = std::array<Point<2>, 2>;
  explicit SegmentBoundary(std::vector<Segment> segments);
  bool inside(double x, double y) const;
  /**
   * The distance from (x, y) to the nearest segment, signed (negative inside), and
   * the outward unit normal there. Costs all segments: fine for a polygon and for a
   * rigid 2D mesh of some hundred boundary faces.
   */
  double signed_distance(double x, double y, Tensor<1, 2> &normal) const;
  const Point<2> &lower() const { return lo; }
  const Point<2> &upper() const { return hi; }
  std::size_t size() const { return segments.size(); }

private:
  /// The strip holding height @p y (clamped to the strips).
  unsigned int strip_of(double y) const;

  std::vector<Segment> segments;
  Point<2> lo, hi;
  double strip_height = 1;
  std::vector<std::vector<unsigned int>> strips;
};

/**
 * A closed surface of triangles in 3D (a 3D mesh's boundary, its quadrilateral faces
 * split in two). Inside by the parity of the crossings of a ray along +x; the
 * triangles are binned by their projection onto the y-z plane, and a ray through an
 * edge or vertex shared by two triangles is counted once (the top-left rule of
 * rasterisers), so that points at mesh vertices' coordinates are classified right.
 */
class TriangleBoundary
{
public:
  using Triangle = std::array<Point<3>, 3>;
  explicit TriangleBoundary(const std::vector<Triangle> &triangles);
  bool inside(const Point<3> &x) const;
  const Point<3> &lower() const { return lo; }
  const Point<3> &upper() const { return hi; }
  std::size_t size() const { return triangles.size(); }

private:
  /// The bin along axis @p d (1: y, 2: z) holding coordinate @p v, clamped.
  unsigned int bin_along(double v, unsigned int d) const;

  /// Triangles with a nonzero projection onto y-z, counter-clockwise there.
  std::vector<Triangle> triangles;
  Point<3> lo, hi;
  unsigned int n_bins = 1;
  double bin_y = 1, bin_z = 1;
  std::vector<std::vector<unsigned int>> bins;
};

/**
 * `polygon(x1, y1, x2, y2, ..., xn, yn)`: the polygon through n >= 3 vertices
 * (closed back to the first), a prism along z through the whole grid in 3D. An exact
 * surface (Surface = exact) too.
 */
template <int dim>
std::unique_ptr<Geometry<dim>> create_polygon(const std::vector<double> &vertices);

/**
 * `mesh(file[, scale][, format])`: the region a mesh file covers, read with deal.II's
 * GridIn (format from the file's extension: .msh Gmsh, .inp Abaqus, .ucd UCD, .vtk
 * VTK, .unv UNV, or named), its coordinates multiplied by scale (default 1, e.g.
 * 0.001 for a mesh in millimetres). The file name is relative to the working
 * directory. @p entry names the parameter in messages.
 */
template <int dim>
std::unique_ptr<Geometry<dim>> create_mesh_shape(const std::string &arguments,
                                                 const std::string &entry);
} // namespace lme_mpm

#endif
