#include <lme_mpm/base/input.h>
#include <lme_mpm/geometry/boundary_shapes.h>
#include <lme_mpm/geometry/geometry.h>

#include <array>
#include <cmath>
#include <stdexcept>

namespace lme_mpm
{
namespace
{
template <int dim>
Point<dim> point_from(const std::vector<double> &a, const unsigned int first)
{
  Point<dim> p;
  for (unsigned int d = 0; d < dim; ++d)
    p[d] = a[first + d];
  return p;
}

/// Axis-aligned box: lower corner, upper corner.
template <int dim>
class Box : public Geometry<dim>
{
public:
  explicit Box(const std::vector<double> &a)
      : lo(point_from<dim>(a, 0)), hi(point_from<dim>(a, dim))
  {
    for (unsigned int d = 0; d < dim; ++d)
      if (!(hi[d] > lo[d]))
        throw std::invalid_argument("rectangle: upper corner must exceed lower");
  }
  bool inside(const Point<dim> &x) const override
  {
    for (unsigned int d = 0; d < dim; ++d)
      if (x[d] < lo[d] || x[d] > hi[d])
        return false;
    return true;
  }
  BoundingBox<dim> bounding_box() const override { return BoundingBox<dim>({lo, hi}); }
  bool signed_distance(const Point<dim> &x, double &distance,
                       Tensor<1, dim> &normal) const override
  {
    // Per direction the distance outside the slab (negative inside it).
    Tensor<1, dim> q, outside;
    unsigned int deepest = 0;
    for (unsigned int d = 0; d < dim; ++d)
    {
      const double below = lo[d] - x[d], above = x[d] - hi[d];
      q[d]       = std::max(below, above);
      outside[d] = q[d] > 0 ? (below > above ? -q[d] : q[d]) : 0.0;
      if (q[d] > q[deepest])
        deepest = d;
    }
    const double out = outside.norm();
    if (out > 0)
    {
      distance = out;
      normal   = outside / out;
      return true;
    }
    // Inside: the nearest face.
    distance        = q[deepest];
    normal          = Tensor<1, dim>();
    normal[deepest] = x[deepest] - lo[deepest] < hi[deepest] - x[deepest] ? -1.0 : 1.0;
    return true;
  }

private:
  Point<dim> lo, hi;
};

/// Disc (2D) or ball (3D): centre, radius.
template <int dim>
class Ball : public Geometry<dim>
{
public:
  explicit Ball(const std::vector<double> &a) : c(point_from<dim>(a, 0)), r(a[dim])
  {
    if (!(r > 0))
      throw std::invalid_argument("disc: the radius must be positive");
  }
  bool inside(const Point<dim> &x) const override { return x.distance(c) <= r; }
  BoundingBox<dim> bounding_box() const override
  {
    Point<dim> lo = c, hi = c;
    for (unsigned int d = 0; d < dim; ++d)
      lo[d] -= r, hi[d] += r;
    return BoundingBox<dim>({lo, hi});
  }
  bool signed_distance(const Point<dim> &x, double &distance,
                       Tensor<1, dim> &normal) const override
  {
    const Tensor<1, dim> a = x - c;
    const double l         = a.norm();
    distance               = l - r;
    normal                 = Tensor<1, dim>();
    if (l > 0)
      normal = a / l;
    else
      normal[dim - 1] = 1;
    return true;
  }

protected:
  Point<dim> c;
  double r;
};

/**
 * Circular cylinder along z: axis (cx, cy), radius, and in 3D the end planes z0 < z1.
 * In 2D the disc, so that one scene description serves both.
 */
template <int dim>
class Cylinder : public Geometry<dim>
{
public:
  explicit Cylinder(const std::vector<double> &a)
      : cx(a[0]), cy(a[1]), r(a[2]), z0(dim == 3 ? a[3] : 0), z1(dim == 3 ? a[4] : 0)
  {
    if (!(r > 0))
      throw std::invalid_argument("cylinder: the radius must be positive");
    if (dim == 3 && !(z1 > z0))
      throw std::invalid_argument("cylinder: z1 must exceed z0");
  }
  bool inside(const Point<dim> &x) const override
  {
    const double dx = x[0] - cx, dy = x[1] - cy;
    return dx * dx + dy * dy <= r * r &&
           (dim < 3 || (x[dim - 1] >= z0 && x[dim - 1] <= z1));
  }
  BoundingBox<dim> bounding_box() const override
  {
    Point<dim> lo, hi;
    lo[0] = cx - r, hi[0] = cx + r, lo[1] = cy - r, hi[1] = cy + r;
    if (dim == 3)
      lo[dim - 1] = z0, hi[dim - 1] = z1;
    return BoundingBox<dim>({lo, hi});
  }
  bool signed_distance(const Point<dim> &x, double &distance,
                       Tensor<1, dim> &normal) const override
  {
    // The lateral surface, and in 3D the end planes: a box in (radius, z).
    const double dx = x[0] - cx, dy = x[1] - cy;
    const double l = std::sqrt(dx * dx + dy * dy), radial = l - r;
    Tensor<1, dim> n_radial;
    if (l > 0)
      n_radial[0] = dx / l, n_radial[1] = dy / l;
    else
      n_radial[1] = 1;
    normal   = n_radial;
    distance = radial;
    if (dim < 3)
      return true;
    const double below = z0 - x[dim - 1], above = x[dim - 1] - z1;
    const double axial = std::max(below, above);
    Tensor<1, dim> n_axial;
    n_axial[dim - 1] = below > above ? -1.0 : 1.0;
    if (radial > 0 && axial > 0)
    {
      distance = std::sqrt(radial * radial + axial * axial);
      normal   = (radial * n_radial + axial * n_axial) / distance;
    }
    else if (axial > radial)
      distance = axial, normal = n_axial;
    return true;
  }

private:
  double cx, cy, r, z0, z1;
};

/**
 * Half disc: centre of the flat edge, radius, and the direction (degrees from +x in
 * the x-y plane) of the curved side. In 3D a half cylinder along z, unbounded in z.
 */
template <int dim>
class HalfDisc : public Geometry<dim>
{
public:
  explicit HalfDisc(const std::vector<double> &a)
      : cx(a[0]), cy(a[1]), r(a[2]), nx(std::cos(a[3] * M_PI / 180)),
        ny(std::sin(a[3] * M_PI / 180))
  {
    if (!(r > 0))
      throw std::invalid_argument("half_disc: the radius must be positive");
  }
  bool inside(const Point<dim> &x) const override
  {
    const double dx = x[0] - cx, dy = x[1] - cy;
    return dx * dx + dy * dy <= r * r && dx * nx + dy * ny >= 0;
  }
  BoundingBox<dim> bounding_box() const override
  {
    // The flat edge's ends, and the arc's extreme points along +-x and +-y that lie
    // on the curved side: the half disc's own box, not the full disc's.
    double x0 = std::min(cx - r * ny, cx + r * ny),
           x1 = std::max(cx - r * ny, cx + r * ny);
    double y0 = std::min(cy + r * nx, cy - r * nx),
           y1 = std::max(cy + r * nx, cy - r * nx);
    if (nx >= 0)
      x1 = cx + r;
    if (nx <= 0)
      x0 = cx - r;
    if (ny >= 0)
      y1 = cy + r;
    if (ny <= 0)
      y0 = cy - r;
    Point<dim> lo, hi;
    lo[0] = x0, hi[0] = x1, lo[1] = y0, hi[1] = y1;
    for (unsigned int d = 2; d < dim; ++d)
      lo[d] = -1e300, hi[d] = 1e300;
    return BoundingBox<dim>({lo, hi});
  }

private:
  double cx, cy, r, nx, ny;
};

/**
 * Slot (a notch): a rectangle of given length and width that starts at a point and
 * runs in a direction (degrees from +x). Unbounded in z in 3D.
 */
template <int dim>
class Slot : public Geometry<dim>
{
public:
  explicit Slot(const std::vector<double> &a)
      : x0(a[0]), y0(a[1]), length(a[2]), width(a[3]), tx(std::cos(a[4] * M_PI / 180)),
        ty(std::sin(a[4] * M_PI / 180))
  {
    if (!(length > 0 && width > 0))
      throw std::invalid_argument("slot: length and width must be positive");
  }
  bool inside(const Point<dim> &x) const override
  {
    const double dx = x[0] - x0, dy = x[1] - y0;
    const double s = dx * tx + dy * ty, n = -dx * ty + dy * tx;
    return s >= 0 && s <= length && std::abs(n) <= 0.5 * width;
  }
  BoundingBox<dim> bounding_box() const override
  {
    // The rectangle's four corners.
    Point<dim> lo, hi;
    lo[0] = lo[1] = 1e300, hi[0] = hi[1] = -1e300;
    for (const double s : {0.0, length})
      for (const double n : {-0.5 * width, 0.5 * width})
      {
        const double x = x0 + s * tx - n * ty, y = y0 + s * ty + n * tx;
        lo[0] = std::min(lo[0], x), hi[0] = std::max(hi[0], x);
        lo[1] = std::min(lo[1], y), hi[1] = std::max(hi[1], y);
      }
    for (unsigned int d = 2; d < dim; ++d)
      lo[d] = -1e300, hi[d] = 1e300;
    return BoundingBox<dim>({lo, hi});
  }

private:
  double x0, y0, length, width, tx, ty;
};

/**
 * A box turned out of the grid's axes: centre, side lengths along its own axes and the
 * turn. In 2D `turned_box(cx, cy, length, width, angle)`, the length along `angle`
 * (degrees from +x). In 3D `turned_box(cx, cy, cz, length, width, depth, angle,
 * out_of_plane_angle)`: the length axis is turned by `angle` about z and then tilted
 * towards +z by `out_of_plane_angle` (a turn about the turned y axis), so it points
 * along (cos b cos a, cos b sin a, sin b); the width lies along the turned y axis
 * (-sin a, cos a, 0) and the depth along their cross product.
 */
template <int dim>
class TurnedBox : public Geometry<dim>
{
public:
  explicit TurnedBox(const std::vector<double> &a) : centre(point_from<dim>(a, 0))
  {
    for (unsigned int d = 0; d < dim; ++d)
    {
      half[d] = 0.5 * a[dim + d];
      if (!(half[d] > 0))
        throw std::invalid_argument("turned_box: the side lengths must be positive");
    }
    const double t = a[2 * dim] * M_PI / 180;
    const double b = dim == 3 ? a[2 * dim + 1] * M_PI / 180 : 0.0;
    axes[0][0] = std::cos(b) * std::cos(t), axes[0][1] = std::cos(b) * std::sin(t);
    axes[1][0] = -std::sin(t), axes[1][1] = std::cos(t);
    if constexpr (dim == 3)
    {
      axes[0][2] = std::sin(b);
      axes[2]    = cross_product_3d(axes[0], axes[1]);
    }
  }
  bool inside(const Point<dim> &x) const override
  {
    const Tensor<1, dim> l = local(x);
    for (unsigned int d = 0; d < dim; ++d)
      if (std::abs(l[d]) > half[d])
        return false;
    return true;
  }
  BoundingBox<dim> bounding_box() const override
  {
    // Over the 2^dim corners.
    Point<dim> lo, hi;
    for (unsigned int d = 0; d < dim; ++d)
      lo[d] = 1e300, hi[d] = -1e300;
    for (unsigned int corner = 0; corner < (1u << dim); ++corner)
    {
      Point<dim> p = centre;
      for (unsigned int k = 0; k < dim; ++k)
        p += ((corner >> k) & 1 ? half[k] : -half[k]) * axes[k];
      for (unsigned int d = 0; d < dim; ++d)
        lo[d] = std::min(lo[d], p[d]), hi[d] = std::max(hi[d], p[d]);
    }
    return BoundingBox<dim>({lo, hi});
  }
  bool signed_distance(const Point<dim> &x, double &distance,
                       Tensor<1, dim> &normal) const override
  {
    // The axis-aligned box's rule in the box's own axes, the normal turned back.
    const Tensor<1, dim> l = local(x);
    Tensor<1, dim> q, outside;
    unsigned int deepest = 0;
    for (unsigned int k = 0; k < dim; ++k)
    {
      q[k]       = std::abs(l[k]) - half[k];
      outside[k] = q[k] > 0 ? (l[k] < 0 ? -q[k] : q[k]) : 0.0;
      if (q[k] > q[deepest])
        deepest = k;
    }
    Tensor<1, dim> n_local;
    const double out = outside.norm();
    if (out > 0)
      distance = out, n_local = outside / out;
    else
      distance = q[deepest], n_local[deepest] = l[deepest] < 0 ? -1.0 : 1.0;
    normal = Tensor<1, dim>();
    for (unsigned int k = 0; k < dim; ++k)
      normal += n_local[k] * axes[k];
    return true;
  }

private:
  Tensor<1, dim> local(const Point<dim> &x) const
  {
    Tensor<1, dim> l;
    for (unsigned int k = 0; k < dim; ++k)
      l[k] = (x - centre) * axes[k];
    return l;
  }

  Point<dim> centre;
  Tensor<1, dim> half;
  std::array<Tensor<1, dim>, dim> axes;
};

template <int dim, class Shape>
typename GeometryRegistry<dim>::Create make()
{
  return [](const std::vector<double> &a) { return std::make_unique<Shape>(a); };
}
} // namespace

template <int dim>
GeometryRegistry<dim> &GeometryRegistry<dim>::instance()
{
  static GeometryRegistry<dim> registry;
  static const bool built_in = []
  {
    registry.add("rectangle", {2 * dim,
                               dim == 2 ? "rectangle(x0, y0, x1, y1)"
                                        : "rectangle(x0, y0, z0, x1, y1, z1)",
                               make<dim, Box<dim>>()});
    registry.add("disc",
                 {dim + 1, dim == 2 ? "disc(cx, cy, r)" : "disc(cx, cy, cz, r): a ball",
                  make<dim, Ball<dim>>()});
    registry.add("cylinder", {dim == 2 ? 3u : 5u,
                              dim == 2 ? "cylinder(cx, cy, r): the disc"
                                       : "cylinder(cx, cy, r, z0, z1): axis along z",
                              make<dim, Cylinder<dim>>()});
    registry.add("half_disc",
                 {4,
                  "half_disc(cx, cy, r, angle): flat edge through (cx, cy), curved "
                  "side towards angle (degrees from +x)",
                  make<dim, HalfDisc<dim>>()});
    registry.add("slot", {5,
                          "slot(x, y, length, width, angle): a notch from (x, y) "
                          "towards angle (degrees from +x)",
                          make<dim, Slot<dim>>()});
    registry.add("turned_box",
                 {dim == 2 ? 5u : 8u,
                  dim == 2 ? "turned_box(cx, cy, length, width, angle): a rectangle "
                             "centred on (cx, cy), its length along angle (degrees "
                             "from +x)"
                           : "turned_box(cx, cy, cz, length, width, depth, angle, "
                             "out_of_plane_angle): a box centred on (cx, cy, cz), its "
                             "length along (cos b cos a, cos b sin a, sin b) for a = "
                             "angle, b = out_of_plane_angle (degrees), its width along "
                             "(-sin a, cos a, 0)",
                  make<dim, TurnedBox<dim>>()});
    registry.add("polygon",
                 {Entry::any_number,
                  dim == 2 ? "polygon(x1, y1, x2, y2, ..., xn, yn): n >= 3 vertices"
                           : "polygon(x1, y1, ..., xn, yn): a prism along z of n >= 3 "
                             "vertices",
                  [](const std::vector<double> &a) { return create_polygon<dim>(a); }});
    registry.add("mesh", {0,
                          "mesh(file[, scale][, format]): the region a mesh file "
                          "covers (Gmsh .msh, Abaqus .inp, UCD, VTK, UNV; read by "
                          "deal.II's GridIn, path relative to the working directory), "
                          "coordinates times scale",
                          {},
                          [](const std::string &args, const std::string &entry)
                          { return create_mesh_shape<dim>(args, entry); }});
    return true;
  }();
  (void)built_in;
  return registry;
}

template <int dim>
std::unique_ptr<Geometry<dim>>
GeometryRegistry<dim>::create(const std::string &text, const std::string &entry) const
{
  const std::string t    = input::trim(text);
  const auto open        = t.find('(');
  const std::string name = input::trim(t.substr(0, open));
  const Entry *shape     = this->find(name);
  AssertThrow(shape != nullptr, ExcBadInput(entry, "unknown shape '" + name +
                                                       "'; known: " + documentation()));
  if (shape->create_from_text)
  {
    AssertThrow(
        open != std::string::npos && t.back() == ')',
        ExcBadInput(entry, "expected " + shape->description + ", got '" + text + "'"));
    return shape->create_from_text(t.substr(open + 1, t.size() - open - 2), entry);
  }
  const input::Call call = input::parse_call(text, entry);
  AssertThrow(shape->n_arguments == Entry::any_number ||
                  call.args.size() == shape->n_arguments,
              ExcBadInput(entry, "'" + call.name + "' takes " +
                                     std::to_string(shape->n_arguments) +
                                     " numbers: " + shape->description));
  try
  {
    return shape->create(call.args);
  }
  catch (const std::invalid_argument &e)
  {
    AssertThrow(false, ExcBadInput(entry, std::string(e.what()) + " in '" + text + "'"));
  }
  return nullptr;
}

template <int dim>
std::string GeometryRegistry<dim>::documentation() const
{
  std::string s;
  for (const auto &e : this->all())
    s += (s.empty() ? "" : "; ") + e.second.description;
  return s;
}

template class GeometryRegistry<2>;
template class GeometryRegistry<3>;
} // namespace lme_mpm
