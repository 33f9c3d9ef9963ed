#include <lme_mpm/base/format.h>
#include <lme_mpm/base/input.h>
#include <lme_mpm/base/parameters.h>
#include <lme_mpm/geometry/bodies.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>

namespace lme_mpm
{
namespace
{
/// The body's own entry beside ParticleGenerator's.
struct NameEntry
{
  std::string name;
  void entries(EntryList &list)
  {
    list.add("Name", name, "", Patterns::Anything(),
             "Name of the body in history.csv (force_<name>_x, displacement_<name>_x, "
             "...) and summary.json: letters, digits or '_'. Empty: not reported.");
  }
};
const char *const velocity_documentation =
    "Velocity (m/s) the body follows, a function of x, y, z and t with one component "
    "per direction separated by ';'. Empty: the body moves freely. A prescribed body "
    "is rigid; it needs Contact/Type = multi-field.";
} // namespace

template <int dim>
void Bodies<dim>::declare_parameters(ParameterHandler &prm, const unsigned int n_bodies)
{
  for (unsigned int b = 0; b < n_bodies; ++b)
  {
    prm.enter_subsection(input::subsection_name("Body", b));
    EntryList::declare<NameEntry>(prm);
    prm.enter_subsection("Prescribed velocity");
    Functions::ParsedFunction<dim>::declare_parameters(prm, dim);
    prm.declare_entry("Function expression", "", Patterns::Anything(),
                      velocity_documentation);
    prm.leave_subsection();
    prm.leave_subsection();
  }
}

template <int dim>
void Bodies<dim>::parse_parameters(ParameterHandler &prm, const unsigned int n_bodies,
                                   const std::vector<std::string> &reserved_names)
{
  names_.assign(n_bodies, "");
  flags.assign(n_bodies, 0);
  exact_flags.assign(n_bodies, 0);
  factor.assign(n_bodies, 1.0);
  functions.clear();
  functions.resize(n_bodies);
  entries.assign(n_bodies, "");
  constant.assign(n_bodies, 0);
  constant_value.assign(n_bodies, Tensor<1, dim>());
  n_prescribed = 0;
  for (unsigned int b = 0; b < n_bodies; ++b)
  {
    const std::string section = input::subsection_name("Body", b);
    prm.enter_subsection(section);
    names_[b] = input::trim(EntryList::parse<NameEntry>(prm).name);
    prm.enter_subsection("Prescribed velocity");
    const std::string expr = input::trim(prm.get("Function expression"));
    prm.leave_subsection();
    if (!expr.empty())
    {
      entries[b]   = section + "/Prescribed velocity";
      functions[b] = std::make_unique<Functions::ParsedFunction<dim>>(dim);
      input::parse_function(prm, "Prescribed velocity", *functions[b], entries[b]);
      flags[b] = 1;
      ++n_prescribed;
      // Evaluated once here either way: a velocity that is not finite at the start
      // stops the run before anything is written.
      const Tensor<1, dim> v0 = velocity(b, Point<dim>(), 0);
      if (!input::depends_on_space_or_time(expr))
        constant_value[b] = v0, constant[b] = 1;
    }
    // Declared with the body's shape (ParticleGenerator), read here for its rule.
    exact_flags[b] = prm.get("Surface") == "exact";
    AssertThrow(!exact_flags[b] || flags[b],
                ExcBadInput(section + "/Surface",
                            "'exact' is a rigid surface that moves as prescribed: give "
                            "the body a Prescribed velocity"));
    prm.leave_subsection();

    const std::string &n = names_[b];
    AssertThrow(
        std::all_of(n.begin(), n.end(),
                    [](const char c)
                    { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }),
        ExcBadInput(section + "/Name", "'" + n + "' must be letters, digits or '_'"));
    if (n.empty())
      continue;
    for (unsigned int o = 0; o < b; ++o)
      AssertThrow(names_[o] != n,
                  ExcBadInput(section + "/Name", "'" + n + "' is also the name of " +
                                                     input::subsection_name("Body", o)));
    for (const auto &r : reserved_names)
      AssertThrow(r != n, ExcBadInput(section + "/Name",
                                      "'" + n +
                                          "' is also the name of a constraint "
                                          "set (history.csv columns would clash)"));
  }
  AssertThrow(n_prescribed < n_bodies || n_bodies == 0,
              ExcBadInput("Body 1/Prescribed velocity",
                          "every body is prescribed: nothing is left to compute"));
}

template <int dim>
bool Bodies<dim>::any_prescribed_particles() const
{
  for (unsigned int b = 0; b < size(); ++b)
    if (flags[b] && !exact_flags[b])
      return true;
  return false;
}

template <int dim>
bool Bodies<dim>::any_exact() const
{
  return std::any_of(exact_flags.begin(), exact_flags.end(),
                     [](const std::uint8_t f) { return f != 0; });
}

template <int dim>
bool Bodies<dim>::any_named() const
{
  return std::any_of(names_.begin(), names_.end(),
                     [](const std::string &n) { return !n.empty(); });
}

template <int dim>
std::string Bodies<dim>::first_prescribed_entry() const
{
  for (const auto &e : entries)
    if (!e.empty())
      return e;
  return "Body 1/Prescribed velocity";
}

template <int dim>
Tensor<1, dim> Bodies<dim>::entry_velocity(const unsigned int b, const Point<dim> &x,
                                           const double t) const
{
  if (constant[b])
    return constant_value[b];
  auto &f = *functions[b];
  f.set_time(t);
  Tensor<1, dim> v;
  for (unsigned int d = 0; d < dim; ++d)
  {
    v[d] = f.value(x, d);
    if (!std::isfinite(v[d]))
    {
      std::ostringstream msg;
      msg << "component "
          << "xyz"[d] << " is " << v[d] << " at " << point_to_string(x) << ", t = " << t
          << " s";
      AssertThrow(false, ExcBadInput(entries[b], msg.str()));
    }
  }
  return v;
}

template <int dim>
Tensor<1, dim> Bodies<dim>::acceleration(const unsigned int b, const Point<dim> &x,
                                         const double t, const double h) const
{
  if (constant[b])
    return Tensor<1, dim>();
  return (velocity(b, x, t + h) - velocity(b, x, t - h)) / (2 * h);
}

template <int dim>
void Bodies<dim>::set_prescribed_velocities(ParticleStore<dim> &store,
                                            const double t) const
{
  if (n_prescribed == 0)
    return;
  for (std::size_t p = 0; p < store.size(); ++p)
    if (flags[store.body_id[p]])
      store.velocity[p] = velocity(store.body_id[p], store.position[p], t);
}

template <int dim>
void Bodies<dim>::write_header(std::ostream &out, const bool forces) const
{
  for (const auto &name : names_)
  {
    if (name.empty())
      continue;
    if (forces)
      for (const char *q : {"", "mean_"})
        for (unsigned int d = 0; d < dim; ++d)
          out << ",force_" << name << "_" << q << "xyz"[d];
    for (unsigned int d = 0; d < dim; ++d)
      out << ",displacement_" << name << "_"
          << "xyz"[d];
  }
}

template <int dim>
void Bodies<dim>::write_row(std::ostream &out, const ParticleStore<dim> &store,
                            const std::vector<Tensor<1, dim>> *forces,
                            const std::vector<Tensor<1, dim>> *mean_forces,
                            const std::vector<Tensor<1, dim>> *rigid_displacements) const
{
  if (!any_named())
    return;
  const unsigned int n = size();
  std::vector<Tensor<1, dim>> moment(n);
  std::vector<double> mass(n, 0.0);
  for (std::size_t p = 0; p < store.size(); ++p)
  {
    const unsigned int b = store.body_id[p];
    moment[b] += store.mass[p] * (store.position[p] - store.reference_position[p]);
    mass[b] += store.mass[p];
  }
  for (unsigned int b = 0; b < n; ++b)
  {
    if (names_[b].empty())
      continue;
    if (forces)
      for (const auto *f : {forces, mean_forces})
        for (unsigned int d = 0; d < dim; ++d)
          out << "," << (*f)[b][d];
    const bool rigid = exact(b) && rigid_displacements;
    for (unsigned int d = 0; d < dim; ++d)
      out << ","
          << (rigid ? (*rigid_displacements)[b][d]
                    : (mass[b] > 0 ? moment[b][d] / mass[b] : 0.0));
  }
}

template class Bodies<2>;
template class Bodies<3>;
} // namespace lme_mpm
