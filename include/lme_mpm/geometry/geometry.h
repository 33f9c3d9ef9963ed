#ifndef LME_MPM_GEOMETRY_GEOMETRY_H
#define LME_MPM_GEOMETRY_GEOMETRY_H

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/point.h>

#include <lme_mpm/base/dealii.h>
#include <lme_mpm/base/registry.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace lme_mpm
{
/**
 * A solid region of space, written in a parameter file as `name(a, b, ...)`, for
 * example `rectangle(0, 0, 1, 0.1)` or `slot(0, 0.5, 0.25, 0.01, 0)`. Bodies are a
 * shape minus holes; particles are kept where inside() holds.
 */
template <int dim>
class Geometry
{
public:
  virtual ~Geometry()                            = default;
  virtual bool inside(const Point<dim> &x) const = 0;
  virtual BoundingBox<dim> bounding_box() const  = 0;
  /**
   * The signed distance from @p x to the shape's surface (negative inside) and the
   * outward unit normal at the nearest surface point. A body whose `Surface` is
   * `exact` touches the others through it (RigidSurfaces); shapes without an exact
   * surface return false and set nothing.
   */
  virtual bool signed_distance(const Point<dim> & /*x*/, double & /*distance*/,
                               Tensor<1, dim> & /*normal*/) const
  {
    return false;
  }
};

/**
 * What GeometryRegistry keeps of one shape: `name(a, b, ...)` with @p n_arguments
 * numbers (or any_number, the shape checking its own list) handed to @p create; or,
 * where @p create_from_text is set, the text between the parentheses as written (a
 * file name and its options) handed to it.
 */
template <int dim>
struct GeometryEntry
{
  using Create =
      std::function<std::unique_ptr<Geometry<dim>>(const std::vector<double> &)>;
  using CreateFromText                     = std::function<std::unique_ptr<Geometry<dim>>(
      const std::string &, const std::string &)>;
  static constexpr unsigned int any_number = static_cast<unsigned int>(-1);
  unsigned int n_arguments;
  std::string description;
  Create create;
  /// Takes the arguments' text and the entry's name (for messages).
  CreateFromText create_from_text = {};
};

/**
 * Shapes by name, on the storage of the plug-in registries (NamedEntries). A user
 * adds one with GeometryRegistry<dim>::instance().add(name, {n_arguments,
 * description, create}) from a static initialiser in their own source file.
 */
template <int dim>
class GeometryRegistry : public NamedEntries<GeometryEntry<dim>>
{
public:
  using Entry  = GeometryEntry<dim>;
  using Create = typename Entry::Create;

  /// The registry, with the built-in shapes.
  static GeometryRegistry &instance();
  /// Parses `name(args)`; @p entry names the parameter in error messages.
  std::unique_ptr<Geometry<dim>> create(const std::string &text,
                                        const std::string &entry) const;
  /// The shapes' descriptions joined by "; ".
  std::string documentation() const;
};
} // namespace lme_mpm

#endif
