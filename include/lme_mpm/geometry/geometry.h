#ifndef LME_MPM_GEOMETRY_GEOMETRY_H
#define LME_MPM_GEOMETRY_GEOMETRY_H

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/point.h>

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace lme_mpm
{
using namespace dealii;

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
};

/**
 * Shapes by name. A user adds one with GeometryRegistry<dim>::instance().add(...)
 * from a static initialiser in their own source file.
 */
template <int dim>
class GeometryRegistry
{
public:
  using Create =
      std::function<std::unique_ptr<Geometry<dim>>(const std::vector<double> &)>;
  struct Entry
  {
    unsigned int n_arguments;
    std::string description;
    Create create;
  };

  static GeometryRegistry &instance();
  bool add(const std::string &name, Entry entry)
  {
    entries[name] = std::move(entry);
    return true;
  }
  /// Parses `name(args)`; @p entry names the parameter in error messages.
  std::unique_ptr<Geometry<dim>> create(const std::string &text,
                                        const std::string &entry) const;
  std::string documentation() const;

private:
  std::map<std::string, Entry> entries;
};
} // namespace lme_mpm

#endif
