#include <lme_mpm/base/input.h>
#include <lme_mpm/scenes/scene.h>

namespace lme_mpm
{
namespace scenes
{
/// A run described by its parameter file alone.
template <int dim>
class GenericScene : public Scene<dim>
{
public:
  explicit GenericScene(const SceneContext<dim> &) {}
};
} // namespace scenes

unsigned int body_number(ParameterHandler &prm, const unsigned int n_bodies,
                         const std::string &name)
{
  for (unsigned int b = 0; b < n_bodies; ++b)
  {
    prm.enter_subsection(input::subsection_name("Body", b));
    const std::string n = input::trim(prm.get("Name"));
    prm.leave_subsection();
    if (n == name)
      return b;
  }
  return n_bodies;
}

unsigned int find_body(ParameterHandler &prm, const unsigned int n_bodies,
                       const std::string &name, const std::string &owner)
{
  const unsigned int b = body_number(prm, n_bodies, name);
  AssertThrow(b < n_bodies, ExcBadInput(owner, "no Body N/Name is '" + name + "'"));
  return b;
}

void set_entry(ParameterHandler &prm, const std::string &entry, const std::string &value,
               const std::string &declared_default, const std::string &owner,
               const std::string &why)
{
  std::vector<std::string> path = input::split(entry, '/');
  const std::string key         = path.back();
  path.pop_back();
  for (const auto &s : path)
    prm.enter_subsection(s);
  const std::string given = input::trim(prm.get(key));
  const bool free         = given == declared_default || given == value;
  if (free)
    prm.set(key, value);
  for (std::size_t i = 0; i < path.size(); ++i)
    prm.leave_subsection();
  AssertThrow(free, ExcBadInput(entry, "is set by " + owner + why + " (to '" + value +
                                           "'): leave it out of the file"));
}

void set_body_entry(ParameterHandler &prm, const unsigned int n_bodies,
                    const std::string &body, const std::string &entry,
                    const std::string &value, const std::string &declared_default,
                    const std::string &owner)
{
  const unsigned int b = find_body(prm, n_bodies, body, owner);
  set_entry(prm, input::subsection_name("Body", b) + "/" + entry, value, declared_default,
            owner, " for body '" + body + "'");
}

EntryWriter::EntryWriter(ParameterHandler &prm, const ParameterHandler &declarations,
                         const unsigned int n_bodies, const unsigned int n_constraints)
    : prm(prm), declarations(declarations), bodies(n_bodies), constraints(n_constraints)
{
}

void EntryWriter::set(const std::string &entry, const std::string &value,
                      const std::string &owner, const std::string &why)
{
  std::vector<std::string> path = input::split(entry, '/');
  const std::string key         = path.back();
  path.pop_back();
  set_entry(prm, entry, value, declarations.get(path, key), owner, why);
}

void EntryWriter::set_body(const std::string &body, const std::string &entry,
                           const std::string &value, const std::string &owner)
{
  set(input::subsection_name("Body", this->body(body, owner)) + "/" + entry, value, owner,
      " for body '" + body + "'");
}

std::string EntryWriter::get(const std::string &entry) const
{
  std::vector<std::string> path = input::split(entry, '/');
  const std::string key         = path.back();
  path.pop_back();
  return input::trim(prm.get(path, key));
}

void EntryWriter::append_item(const std::string &entry, const std::string &item)
{
  const std::string now = get(entry);
  for (const auto &i : input::split(now, ';'))
    if (i == input::trim(item))
      return;
  std::vector<std::string> path = input::split(entry, '/');
  const std::string key         = path.back();
  path.pop_back();
  for (const auto &s : path)
    prm.enter_subsection(s);
  prm.set(key, now.empty() ? input::trim(item) : now + "; " + input::trim(item));
  for (std::size_t i = 0; i < path.size(); ++i)
    prm.leave_subsection();
}

unsigned int EntryWriter::body(const std::string &name, const std::string &owner) const
{
  return find_body(prm, bodies, name, owner);
}

bool EntryWriter::has_body(const std::string &name) const
{
  return body_number(prm, bodies, name) < bodies;
}

unsigned int EntryWriter::constraint(const std::string &name,
                                     const std::string &owner) const
{
  for (unsigned int c = 0; c < constraints; ++c)
    if (get("Boundary conditions/" + input::subsection_name("Constraint", c) + "/Name") ==
        name)
      return c;
  AssertThrow(false,
              ExcBadInput(owner, "no Boundary conditions/Constraint N/Name is '" + name +
                                     "' (Boundary conditions/Number of "
                                     "constraints = " +
                                     std::to_string(constraints) + ")"));
  return constraints;
}

template <int dim>
void declare_scene_parameters(ParameterHandler &prm)
{
  prm.enter_subsection("Scene");
  const auto &registry = SceneRegistry<dim>::instance();
  prm.declare_entry("Type", "none", Patterns::Selection(registry.pattern()),
                    "The scene the run reproduces, for the entries and results "
                    "particular to it: " +
                        registry.documentation());
  registry.declare_all(prm);
  prm.leave_subsection();
}

template <int dim>
std::unique_ptr<Scene<dim>> create_scene(ParameterHandler &prm,
                                         const SceneContext<dim> &context)
{
  const std::string type = prm.get(std::vector<std::string>{"Scene"}, "Type");
  // Another scene's entries would be read by nobody: a value set there is refused.
  if (context.declarations)
    for (const auto &path : input::declared_entries(*context.declarations))
    {
      const auto parts = input::split(path, '/');
      if (parts.size() < 3 || parts[0] != "Scene" || parts[1] == type)
        continue;
      const std::vector<std::string> subsection(parts.begin(), parts.end() - 1);
      AssertThrow(prm.get(subsection, parts.back()) ==
                      context.declarations->get(subsection, parts.back()),
                  ExcBadInput(path, "belongs to the scene '" + parts[1] +
                                        "', but 'Scene/Type' is '" + type +
                                        "': remove it, or select that scene"));
    }
  prm.enter_subsection("Scene");
  auto scene = SceneRegistry<dim>::instance().create(type, prm, context);
  prm.leave_subsection();
  return scene;
}

template void declare_scene_parameters<2>(ParameterHandler &);
template void declare_scene_parameters<3>(ParameterHandler &);
template std::unique_ptr<Scene<2>> create_scene(ParameterHandler &,
                                                const SceneContext<2> &);
template std::unique_ptr<Scene<3>> create_scene(ParameterHandler &,
                                                const SceneContext<3> &);
} // namespace lme_mpm

using lme_mpm::scenes::GenericScene;
LME_MPM_REGISTER_SCENE(GenericScene, "none",
                       "a run described by its parameter file alone.")
