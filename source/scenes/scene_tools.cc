#include <lme_mpm/base/input.h>
#include <lme_mpm/scenes/scene_tools.h>

#include <sstream>

namespace lme_mpm
{
namespace scenes
{
std::string number(const double x)
{
  std::ostringstream s;
  s.precision(15);
  s << x;
  return s.str();
}

void set_notch_crack(EntryWriter &writer, const std::string &body,
                     const std::string &polyline, const std::string &owner)
{
  writer.set("Cracks/Polylines", polyline, owner);
  writer.set("Cracks/Grow with erosion", "false", owner);
  writer.set("Cracks/Body", std::to_string(writer.body(body, owner) + 1), owner);
}

template <int dim>
std::string box_shape(const double x0, const double y0, const double x1, const double y1,
                      const double length)
{
  if (dim == 2)
    return "rectangle(" + number(x0) + ", " + number(y0) + ", " + number(x1) + ", " +
           number(y1) + ")";
  return "rectangle(" + number(x0) + ", " + number(y0) + ", 0, " + number(x1) + ", " +
         number(y1) + ", " + number(length) + ")";
}

template <int dim>
std::string cylinder_shape(const double cx, const double cy, const double r,
                           const double length)
{
  std::string s = "cylinder(" + number(cx) + ", " + number(cy) + ", " + number(r);
  if (dim == 3)
    s += ", 0, " + number(length);
  return s + ")";
}

template <int dim>
std::string ramped_velocity(const double vx, const double vy, const double ramp)
{
  const std::string factor = ramp > 0 ? "(if(t < " + number(ramp) +
                                            ", 0.5 * (1 - cos(pi * t / " + number(ramp) +
                                            ")), 1))"
                                      : "1";
  std::string s = number(vx) + " * " + factor + "; " + number(vy) + " * " + factor;
  if (dim == 3)
    s += "; 0";
  return s;
}

template <int dim>
double damaged_volume(const ParticleStore<dim> &p, const unsigned int body)
{
  double damaged = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.body_id[i] == body && p.damage[i] > 0)
      damaged += p.damage[i] * p.mass[i] / p.density[i];
  return damaged;
}

template <int dim>
unsigned int body_index(const SceneState<dim> &state, const std::string &name,
                        const std::string &entry)
{
  const auto &names = *state.body_names;
  for (unsigned int b = 0; b < names.size(); ++b)
    if (names[b] == name)
      return b;
  AssertThrow(false, ExcBadInput(entry, "no Body N/Name is '" + name + "'"));
  return 0;
}

template <int dim>
const NodeConstraint<dim> &constraint_named(const SceneState<dim> &state,
                                            const std::string &name,
                                            const std::string &entry)
{
  const NodeConstraints<dim> &sets = *state.constraints;
  for (unsigned int c = 0; c < sets.size(); ++c)
    if (sets[c].name() == name)
      return sets[c];
  AssertThrow(false, ExcBadInput(entry, "no Boundary conditions/Constraint N/Name is '" +
                                            name + "'"));
  return sets[0];
}

template <int dim>
Tensor<1, dim> mean_displacement_near(const ParticleStore<dim> &p,
                                      const unsigned int body, const Point<2> &centre,
                                      const double radius)
{
  double m = 0;
  Tensor<1, dim> u;
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    const double dx = p.reference_position[i][0] - centre[0],
                 dy = p.reference_position[i][1] - centre[1];
    if (p.body_id[i] == body && dx * dx + dy * dy <= radius * radius)
    {
      m += p.mass[i];
      u += p.mass[i] * (p.position[i] - p.reference_position[i]);
    }
  }
  return m > 0 ? u / m : u;
}

template std::string box_shape<2>(double, double, double, double, double);
template std::string box_shape<3>(double, double, double, double, double);
template std::string cylinder_shape<2>(double, double, double, double);
template std::string cylinder_shape<3>(double, double, double, double);
template std::string ramped_velocity<2>(double, double, double);
template std::string ramped_velocity<3>(double, double, double);
template double damaged_volume(const ParticleStore<2> &, unsigned int);
template double damaged_volume(const ParticleStore<3> &, unsigned int);
template unsigned int body_index(const SceneState<2> &, const std::string &,
                                 const std::string &);
template unsigned int body_index(const SceneState<3> &, const std::string &,
                                 const std::string &);
template const NodeConstraint<2> &
constraint_named(const SceneState<2> &, const std::string &, const std::string &);
template const NodeConstraint<3> &
constraint_named(const SceneState<3> &, const std::string &, const std::string &);
template Tensor<1, 2> mean_displacement_near(const ParticleStore<2> &, unsigned int,
                                             const Point<2> &, double);
template Tensor<1, 3> mean_displacement_near(const ParticleStore<3> &, unsigned int,
                                             const Point<2> &, double);
} // namespace scenes
} // namespace lme_mpm
