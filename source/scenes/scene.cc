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
  prm.enter_subsection("Scene");
  const std::string type = prm.get("Type");
  auto scene             = SceneRegistry<dim>::instance().create(type, prm, context);
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
