#ifndef LME_MPM_SCENES_SCENE_H
#define LME_MPM_SCENES_SCENE_H

#include <deal.II/base/parameter_handler.h>

#include <lme_mpm/base/registry.h>
#include <lme_mpm/particles/particle_store.h>
#include <lme_mpm/solver/run_parameters.h>

#include <map>
#include <string>
#include <vector>

namespace lme_mpm
{
/// What a scene is built from besides its own entries.
template <int dim>
struct SceneContext
{
  double thickness = 1;
};

/// What a scene sees at the end of a run.
template <int dim>
struct SceneState
{
  const ParticleStore<dim> *particles = nullptr;
  /// "Body N/Name" per body (empty where unnamed).
  const std::vector<std::string> *body_names = nullptr;
  /// The run's parameters, as adjust() left them.
  const RunParameters<dim> *run = nullptr;
  double time                   = 0;
};

/**
 * A scene of the paper or of the test suite: the entries of subsection "Scene" that
 * describe it in its own terms (an incline angle, a notch angle), the run parameters
 * they imply, and the results it reports in summary.json. The bodies, materials and
 * constraints stay in the parameter file; a scene adds what a generic run cannot
 * derive. Scenes register with LME_MPM_REGISTER_SCENE and are chosen by Scene/Type.
 */
template <int dim>
class Scene
{
public:
  virtual ~Scene() = default;
  /// Sets run parameters that follow from the scene's entries (called before the run
  /// is set up); throws ExcBadInput naming the entry on a conflict.
  virtual void adjust(RunParameters<dim> &) const {}
  /// Checks the scene against the set-up run (named bodies exist, ...); throws
  /// ExcBadInput naming the entry.
  virtual void check(const SceneState<dim> &) const {}
  /// Adds the scene's results to summary.json.
  virtual void add_results(const SceneState<dim> &, std::map<std::string, double> &) const
  {
  }
};

template <int dim>
using SceneRegistry = Registry<Scene<dim>, SceneContext<dim>>;

/// Declares "Scene/Type" and every registered scene's entries beside it.
template <int dim>
void declare_scene_parameters(ParameterHandler &prm);
/// Builds the scene Scene/Type names.
template <int dim>
std::unique_ptr<Scene<dim>> create_scene(ParameterHandler &prm,
                                         const SceneContext<dim> &context);
} // namespace lme_mpm

/**
 * Registers scene class template CLASS (templated on dim, constructed from
 * (ParameterHandler &, const SceneContext<dim> &) or the context alone, with an
 * optional static declare_parameters(ParameterHandler &)) as NAME for dim = 2 and 3.
 * Its entries go straight into subsection "Scene".
 */
#define LME_MPM_REGISTER_SCENE(CLASS, NAME, DESCRIPTION)                                 \
  LME_MPM_REGISTER_PLUGIN_FOR_DIMS(::lme_mpm::SceneRegistry, scene, CLASS, NAME,         \
                                   DESCRIPTION,                                          \
                                   ::lme_mpm::PluginEntries::caller_subsection)

#endif
