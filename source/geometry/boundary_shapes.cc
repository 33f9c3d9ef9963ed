#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <lme_mpm/base/input.h>
#include <lme_mpm/geometry/boundary_shapes.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <stdexcept>

namespace lme_mpm
{
SegmentBoundary::SegmentBoundary(std::vector<Segment> s) : segments(std::move(s))
{
  if (segments.empty())
    throw std::invalid_argument("a boundary needs at least one segment");
  lo = hi = segments.front()[0];
  for (const auto &seg : segments)
    for (const auto &p : seg)
      for (unsigned int d = 0; d < 2; ++d)
        lo[d] = std::min(lo[d], p[d]), hi[d] = std::max(hi[d], p[d]);
  if (!(hi[1] > lo[1]) || !(hi[0] > lo[0]))
    throw std::invalid_argument("the boundary encloses no area");
  // About four segments per strip on a boundary that crosses each strip twice.
  const unsigned int n_strips = std::clamp<std::size_t>(segments.size() / 8, 1, 4096);
  strip_height                = (hi[1] - lo[1]) / n_strips;
  strips.resize(n_strips);
  for (unsigned int i = 0; i < segments.size(); ++i)
  {
    const auto &seg = segments[i];
    for (unsigned int k = strip_of(std::min(seg[0][1], seg[1][1]));
         k <= strip_of(std::max(seg[0][1], seg[1][1])); ++k)
      strips[k].push_back(i);
  }
}

unsigned int SegmentBoundary::strip_of(const double y) const
{
  const double s = std::floor((y - lo[1]) / strip_height);
  return static_cast<unsigned int>(std::clamp(s, 0.0, strips.size() - 1.0));
}

bool SegmentBoundary::inside(const double x, const double y) const
{
  if (!(y >= lo[1] && y <= hi[1] && x >= lo[0] && x <= hi[0]))
    return false;
  const unsigned int k = strip_of(y);
  // Crossings of the ray towards +x; a segment counts with one end strictly above y,
  // so that a ray through a vertex meets its two segments once.
  bool in = false;
  for (const unsigned int i : strips[k])
  {
    const Point<2> &a = segments[i][0], &b = segments[i][1];
    if ((a[1] > y) != (b[1] > y))
    {
      const double xc = a[0] + (y - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
      if (x < xc)
        in = !in;
    }
  }
  return in;
}

double SegmentBoundary::signed_distance(const double x, const double y,
                                        Tensor<1, 2> &normal) const
{
  const Point<2> p(x, y);
  double best = std::numeric_limits<double>::max();
  Point<2> nearest;
  Tensor<1, 2> along;
  for (const auto &seg : segments)
  {
    const Tensor<1, 2> t = seg[1] - seg[0];
    const double tt      = t * t;
    const double s       = tt > 0 ? std::clamp((p - seg[0]) * t / tt, 0.0, 1.0) : 0.0;
    const Point<2> q     = seg[0] + s * t;
    const double d       = p.distance(q);
    if (d < best)
      best = d, nearest = q, along = t;
  }
  const bool in = inside(x, y);
  if (best > 1e-14 * (hi - lo).norm())
    normal = (in ? nearest - p : p - nearest) / best;
  else
  {
    // On the boundary: the segment's normal, turned outwards.
    normal             = Tensor<1, 2>({along[1], -along[0]}) / along.norm();
    const double probe = 1e-9 * (hi - lo).norm();
    if (inside(x + probe * normal[0], y + probe * normal[1]))
      normal *= -1.0;
  }
  return in ? -best : best;
}

namespace
{
/// The y-z edge function of (a, b) at p: positive left of a -> b.
double edge(const Point<3> &a, const Point<3> &b, const double y, const double z)
{
  return (b[1] - a[1]) * (z - a[2]) - (b[2] - a[2]) * (y - a[1]);
}

/// Whether a point on the edge a -> b of a counter-clockwise triangle belongs to it:
/// of the two triangles that share an edge exactly one does.
bool owns_edge(const Point<3> &a, const Point<3> &b)
{
  const double dy = b[1] - a[1], dz = b[2] - a[2];
  return dz < 0 || (dz == 0 && dy < 0);
}
} // namespace

TriangleBoundary::TriangleBoundary(const std::vector<Triangle> &all)
{
  if (all.empty())
    throw std::invalid_argument("a boundary needs at least one triangle");
  lo = hi = all.front()[0];
  for (const auto &t : all)
  {
    for (const auto &p : t)
      for (unsigned int d = 0; d < 3; ++d)
        lo[d] = std::min(lo[d], p[d]), hi[d] = std::max(hi[d], p[d]);
    // A triangle parallel to x is grazed by the ray, never crossed.
    Triangle c      = t;
    const double a2 = edge(c[0], c[1], c[2][1], c[2][2]);
    if (a2 == 0)
      continue;
    if (a2 < 0)
      std::swap(c[1], c[2]);
    triangles.push_back(c);
  }
  if (!(hi[0] > lo[0] && hi[1] > lo[1] && hi[2] > lo[2]))
    throw std::invalid_argument("the boundary encloses no volume");
  n_bins = static_cast<unsigned int>(
      std::clamp(std::sqrt(triangles.size() / 2.0), 1.0, 512.0));
  bin_y = (hi[1] - lo[1]) / n_bins, bin_z = (hi[2] - lo[2]) / n_bins;
  bins.resize(n_bins * n_bins);
  for (unsigned int i = 0; i < triangles.size(); ++i)
  {
    const auto &t   = triangles[i];
    const double y0 = std::min({t[0][1], t[1][1], t[2][1]}),
                 y1 = std::max({t[0][1], t[1][1], t[2][1]}),
                 z0 = std::min({t[0][2], t[1][2], t[2][2]}),
                 z1 = std::max({t[0][2], t[1][2], t[2][2]});
    for (unsigned int j = bin_along(y0, 1); j <= bin_along(y1, 1); ++j)
      for (unsigned int k = bin_along(z0, 2); k <= bin_along(z1, 2); ++k)
        bins[j + n_bins * k].push_back(i);
  }
}

unsigned int TriangleBoundary::bin_along(const double v, const unsigned int d) const
{
  const double b = std::floor((v - lo[d]) / (d == 1 ? bin_y : bin_z));
  return static_cast<unsigned int>(std::clamp(b, 0.0, n_bins - 1.0));
}

bool TriangleBoundary::inside(const Point<3> &x) const
{
  for (unsigned int d = 0; d < 3; ++d)
    if (!(x[d] >= lo[d] && x[d] <= hi[d]))
      return false;
  bool in = false;
  for (const unsigned int i : bins[bin_along(x[1], 1) + n_bins * bin_along(x[2], 2)])
  {
    const Triangle &t = triangles[i];
    const double w[3] = {edge(t[1], t[2], x[1], x[2]), edge(t[2], t[0], x[1], x[2]),
                         edge(t[0], t[1], x[1], x[2])};
    bool hit          = true;
    for (unsigned int e = 0; e < 3 && hit; ++e)
      hit = w[e] > 0 || (w[e] == 0 && owns_edge(t[(e + 1) % 3], t[(e + 2) % 3]));
    if (!hit)
      continue;
    const double x_hit =
        (w[0] * t[0][0] + w[1] * t[1][0] + w[2] * t[2][0]) / (w[0] + w[1] + w[2]);
    if (x[0] < x_hit)
      in = !in;
  }
  return in;
}

namespace
{
template <int dim>
BoundingBox<dim> box_of(const Point<2> &lo2, const Point<2> &hi2)
{
  Point<dim> lo, hi;
  for (unsigned int d = 0; d < 2; ++d)
    lo[d] = lo2[d], hi[d] = hi2[d];
  for (unsigned int d = 2; d < dim; ++d)
    lo[d] = -1e300, hi[d] = 1e300;
  return BoundingBox<dim>({lo, hi});
}

/// A region bounded by segments in x-y: in 3D a prism along z, unbounded.
template <int dim>
class SegmentRegion : public Geometry<dim>
{
public:
  explicit SegmentRegion(SegmentBoundary b) : boundary(std::move(b)) {}
  bool inside(const Point<dim> &x) const override { return boundary.inside(x[0], x[1]); }
  BoundingBox<dim> bounding_box() const override
  {
    return box_of<dim>(boundary.lower(), boundary.upper());
  }
  bool signed_distance(const Point<dim> &x, double &distance,
                       Tensor<1, dim> &normal) const override
  {
    Tensor<1, 2> n;
    distance  = boundary.signed_distance(x[0], x[1], n);
    normal    = Tensor<1, dim>();
    normal[0] = n[0], normal[1] = n[1];
    return true;
  }

private:
  SegmentBoundary boundary;
};

/// The region a 3D mesh fills: its closed boundary surface.
class SurfaceRegion : public Geometry<3>
{
public:
  explicit SurfaceRegion(const std::vector<TriangleBoundary::Triangle> &t) : boundary(t)
  {
  }
  bool inside(const Point<3> &x) const override { return boundary.inside(x); }
  BoundingBox<3> bounding_box() const override
  {
    return BoundingBox<3>({boundary.lower(), boundary.upper()});
  }

private:
  TriangleBoundary boundary;
};

/// The format named by @p name or by the extension of @p file.
template <int dim>
typename GridIn<dim>::Format mesh_format(const std::string &file, const std::string &name,
                                         const std::string &entry)
{
  using Format = typename GridIn<dim>::Format;
  const std::vector<std::pair<std::string, Format>> formats = {
      {"msh", Format::msh}, {"abaqus", Format::abaqus}, {"ucd", Format::ucd},
      {"vtk", Format::vtk}, {"unv", Format::unv},       {"inp", Format::abaqus}};
  std::string key = name;
  if (key.empty())
  {
    const auto dot = file.rfind('.');
    key            = dot == std::string::npos ? "" : file.substr(dot + 1);
  }
  for (const auto &f : formats)
    if (f.first == key)
      return f.second;
  AssertThrow(false,
              ExcBadInput(entry, name.empty()
                                     ? "cannot tell the format of '" + file +
                                           "' from its extension: name it, as in mesh(" +
                                           file +
                                           ", msh); known: msh, abaqus, ucd, vtk, unv"
                                     : "unknown mesh format '" + name +
                                           "'; known: msh, abaqus, ucd, vtk, unv"));
  return Format::Default;
}

/// The first line of a deal.II exception's text that says what went wrong.
std::string reason(const std::exception &e)
{
  const std::string what = e.what();
  for (const auto &line : input::split(what, '\n'))
    if (line.find("Additional information") != std::string::npos)
      return line;
  const auto cut = what.find_first_not_of(" \n-");
  return cut == std::string::npos ? what : what.substr(cut, 300);
}
} // namespace

template <int dim>
std::unique_ptr<Geometry<dim>> create_polygon(const std::vector<double> &a)
{
  if (a.size() < 6 || a.size() % 2 != 0)
    throw std::invalid_argument("polygon: needs the x, y of at least three vertices, "
                                "an even count of numbers");
  std::vector<SegmentBoundary::Segment> segments;
  double twice_area   = 0;
  const std::size_t n = a.size() / 2;
  for (std::size_t i = 0; i < n; ++i)
  {
    const std::size_t j = (i + 1) % n;
    const Point<2> p(a[2 * i], a[2 * i + 1]), q(a[2 * j], a[2 * j + 1]);
    if (p == q)
      throw std::invalid_argument("polygon: vertices " + std::to_string(i + 1) + " and " +
                                  std::to_string(j + 1) + " coincide");
    segments.push_back({{p, q}});
    twice_area += p[0] * q[1] - q[0] * p[1];
  }
  if (twice_area == 0)
    throw std::invalid_argument("polygon: the vertices enclose no area");
  return std::make_unique<SegmentRegion<dim>>(SegmentBoundary(std::move(segments)));
}

template <int dim>
std::unique_ptr<Geometry<dim>> create_mesh_shape(const std::string &arguments,
                                                 const std::string &entry)
{
  const auto args = input::split(arguments, ',');
  AssertThrow(!args.empty(),
              ExcBadInput(entry, "mesh(file[, scale][, format]) needs a file name"));
  const std::string &file = args[0];
  double scale            = 1;
  std::string format_name;
  for (std::size_t i = 1; i < args.size(); ++i)
  {
    std::size_t used = 0;
    double v         = 0;
    try
    {
      v = std::stod(args[i], &used);
    }
    catch (...)
    {
      used = 0;
    }
    if (used == args[i].size())
    {
      AssertThrow(std::isfinite(v) && v > 0,
                  ExcBadInput(entry, "the scale of mesh '" + file +
                                         "' must be positive "
                                         "and finite, got " +
                                         args[i]));
      scale = v;
    }
    else
      format_name = args[i];
  }
  const auto format = mesh_format<dim>(file, format_name, entry);
  std::ifstream in(file);
  AssertThrow(in, ExcBadInput(entry, "cannot open the mesh file '" + file +
                                         "' (a path relative to the working directory)"));
  Triangulation<dim> tria;
  try
  {
    GridIn<dim> reader;
    reader.attach_triangulation(tria);
    reader.read(in, format);
  }
  catch (const std::exception &e)
  {
    AssertThrow(false,
                ExcBadInput(entry, "cannot read the mesh file '" + file + "' as a " +
                                       std::to_string(dim) + "D mesh: " + reason(e)));
  }
  AssertThrow(tria.n_active_cells() > 0,
              ExcBadInput(entry, "the mesh file '" + file + "' holds no cell"));
  if (scale != 1)
    GridTools::scale(scale, tria);
  // The region is what the mesh's boundary faces enclose.
  if constexpr (dim == 2)
  {
    std::vector<SegmentBoundary::Segment> segments;
    for (const auto &cell : tria.active_cell_iterators())
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary())
          segments.push_back({{cell->face(f)->vertex(0), cell->face(f)->vertex(1)}});
    return std::make_unique<SegmentRegion<2>>(SegmentBoundary(std::move(segments)));
  }
  else
  {
    std::vector<TriangleBoundary::Triangle> triangles;
    for (const auto &cell : tria.active_cell_iterators())
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary())
        {
          const auto face = cell->face(f);
          // A quadrilateral's vertices are numbered lexicographically: 0 1 3 2 go round.
          triangles.push_back({{face->vertex(0), face->vertex(1), face->vertex(2)}});
          if (face->n_vertices() == 4)
          {
            triangles.back() = {{face->vertex(0), face->vertex(1), face->vertex(3)}};
            triangles.push_back({{face->vertex(0), face->vertex(3), face->vertex(2)}});
          }
        }
    return std::make_unique<SurfaceRegion>(triangles);
  }
}

template std::unique_ptr<Geometry<2>> create_polygon<2>(const std::vector<double> &);
template std::unique_ptr<Geometry<3>> create_polygon<3>(const std::vector<double> &);
template std::unique_ptr<Geometry<2>> create_mesh_shape<2>(const std::string &,
                                                           const std::string &);
template std::unique_ptr<Geometry<3>> create_mesh_shape<3>(const std::string &,
                                                           const std::string &);
} // namespace lme_mpm
