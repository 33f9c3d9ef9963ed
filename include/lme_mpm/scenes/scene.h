#ifndef LME_MPM_SCENES_SCENE_H
#define LME_MPM_SCENES_SCENE_H

#include <deal.II/base/parameter_handler.h>

#include <lme_mpm/base/archive.h>
#include <lme_mpm/base/rank_reductions.h>
#include <lme_mpm/base/registry.h>
#include <lme_mpm/boundary/node_constraints.h>
#include <lme_mpm/grid/background_grid.h>
#include <lme_mpm/output/gauges.h>
#include <lme_mpm/particles/particle_store.h>
#include <lme_mpm/solver/run_parameters.h>

#include <functional>
#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace lme_mpm
{
/// What a scene is built from besides its own entries.
template <int dim>
struct SceneContext
{
  double thickness = 1;
  /// Problem/Number of bodies.
  unsigned int n_bodies = 1;
  /// Boundary conditions/Number of constraints.
  unsigned int n_constraints = 0;
  /// Whether bodies get their own fields (Contact/Type is not 'none').
  bool contact = false;
  /**
   * Every entry as declared (defaults only, nothing parsed), for EntryWriter; valid
   * while the scene is built and writes its entries.
   */
  const ParameterHandler *declarations = nullptr;
};

/**
 * Writes entries of other subsections on behalf of a scene (a body's shape from a
 * strip width, a roller's velocity): the scene expands its own entries into the
 * generic ones. A scene never silently replaces what the user wrote: an entry the
 * file left at its declared default (or gave the scene's value itself) takes the
 * scene's value; any other value stops the run with a message naming both entries.
 */
class EntryWriter
{
public:
  EntryWriter(ParameterHandler &prm, const ParameterHandler &declarations,
              unsigned int n_bodies, unsigned int n_constraints);

  /**
   * Sets @p entry (a path from the top level, 'Cracks/Polylines') to @p value on
   * behalf of scene entry @p owner; @p why is added to the error message after the
   * owner.
   */
  void set(const std::string &entry, const std::string &value, const std::string &owner,
           const std::string &why = "");
  /// Sets @p entry ('Shape', 'Prescribed velocity/Function expression') of the body
  /// named @p body.
  void set_body(const std::string &body, const std::string &entry,
                const std::string &value, const std::string &owner);
  /// The value of @p entry (a path from the top level) now.
  std::string get(const std::string &entry) const;
  /**
   * Adds @p item to the ';'-separated list @p entry ('Output/Opening gauges') after
   * what the file gave, unless the list holds it already (a resumed run's recorded
   * parameters do).
   */
  void append_item(const std::string &entry, const std::string &item);

  /// The index (N - 1) of the "Body N" named @p name; throws naming @p owner if none.
  unsigned int body(const std::string &name, const std::string &owner) const;
  /// True if a "Body N" is named @p name.
  bool has_body(const std::string &name) const;
  /// The index of the "Boundary conditions/Constraint N" named @p name; throws
  /// naming @p owner if none.
  unsigned int constraint(const std::string &name, const std::string &owner) const;
  unsigned int n_constraints() const { return constraints; }

  /// The handler, for scenes written against set_entries(ParameterHandler &).
  ParameterHandler &handler() { return prm; }

private:
  ParameterHandler &prm;
  const ParameterHandler &declarations;
  unsigned int bodies, constraints;
};

/**
 * What a scene sees of the run: after every step (observe(), finished()), in each
 * history row (write_history_row()) and at the end (add_results()).
 */
template <int dim>
struct SceneState
{
  /**
   * The particles. After a step: this rank's (on several MPI ranks some are ghosts,
   * copies of another rank's, flagged in `ghost`: sum over owned() ones and then
   * over the ranks). In a history row and at the end: every particle of the run, on
   * rank 0 (the rank that writes the files).
   */
  const ParticleStore<dim> *particles = nullptr;
  /// "Body N/Name" per body (empty where unnamed).
  const std::vector<std::string> *body_names = nullptr;
  /// The run's parameters, as adjust() left them.
  const RunParameters<dim> *run = nullptr;
  /**
   * Per body: the contact force it received, its mean over the force window
   * (Output/Force window) that ends at this step, and the largest magnitude of that
   * mean so far (empty without contact). Updated every step, so that peaks and stop
   * rules judged on them do not depend on the output cadence.
   */
  const std::vector<Tensor<1, dim>> *contact_forces = nullptr;
  const std::vector<double> *peak_contact_forces    = nullptr;
  /// Per body, in a history row: the contact force's mean over the output interval
  /// the row closes (its impulse over the interval); null after a step.
  const std::vector<Tensor<1, dim>> *contact_force_means = nullptr;
  /// The constrained node sets, with their reactions and impulses.
  const NodeConstraints<dim> *constraints = nullptr;
  /// The opening gauges (Output/Opening gauges, with those the scene added).
  const OpeningGauges<dim> *gauges = nullptr;
  /// After a step: sums and maxima over the MPI ranks (every rank calls them
  /// together; on one rank they return their argument). Null in a history row and at
  /// the end, which rank 0 alone sees.
  const RankReductions *ranks = nullptr;
  /**
   * After a step: every particle of the run, gathered on rank 0 (elsewhere an empty
   * store; on one rank the particles themselves). Every rank must call it at the
   * same step, so decide to on reduced values; it costs a gather of all particles on
   * several ranks.
   */
  std::function<const ParticleStore<dim> &()> all_particles;
  /// The background grid (the whole of it, on every rank).
  const BackgroundGrid<dim> *grid = nullptr;
  double time                     = 0;
  /// The length of the step just taken (0 in a history row or at the end).
  double step_length = 0;
  /// Output/Force window (s): the span of the means scenes judge loads by.
  double force_window = 0;

  /// True if particle @p i is this rank's own (not a ghost).
  bool owned(const std::size_t i) const { return particles->ghost[i] == 0; }
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
  /**
   * Writes entries of other subsections that follow from the scene's own (a body's
   * shape from a strip width, a loading velocity) through @p writer, and reads what
   * the scene needs of them (EntryWriter::get); called right after the scene is
   * built, before anything else reads the file. The default calls set_entries() on
   * the handler.
   */
  virtual void write_entries(EntryWriter &writer) { set_entries(writer.handler()); }
  /// The earlier form of write_entries(): writes into @p prm at its top level with
  /// set_body_entry(). Kept for scenes written against it.
  virtual void set_entries(ParameterHandler &) const {}
  /// Checks the scene against the set-up run (named bodies exist, ...); throws
  /// ExcBadInput naming the entry.
  virtual void check(const SceneState<dim> &) const {}
  /// The scene's own history.csv columns, each preceded by a comma.
  virtual void write_history_header(std::ostream &) const {}
  /// Their values in one history row, each preceded by a comma.
  virtual void write_history_row(std::ostream &, const SceneState<dim> &) const {}
  /**
   * Called after every step on every rank (the state holds this rank's particles):
   * the scene tracks here what its results take the largest value, the time of a
   * maximum or a threshold crossing of, so that they do not depend on how often
   * history rows are written. Keep it cheap: it runs as often as the step.
   */
  virtual void observe(const SceneState<dim> &) {}
  /**
   * Asked after every step, after observe(): a non-empty answer ends the run there,
   * with the answer as the reason in summary.json (a load test stops once the
   * specimen has failed, as a testing machine does). Every rank must give the same
   * answer (judge on reduced values). The default never stops early.
   */
  virtual std::string finished(const SceneState<dim> &) const { return {}; }
  /// Saves or loads what the scene has accumulated over the run (the peaks observe()
  /// tracks), so that a resumed run reports the same as an uninterrupted one. The
  /// default has nothing to keep.
  virtual void serialize(Archive &) {}
  /// Adds the scene's results to summary.json.
  virtual void add_results(const SceneState<dim> &, std::map<std::string, double> &) const
  {
  }
};

template <int dim>
using SceneRegistry = Registry<Scene<dim>, SceneContext<dim>>;

/// The N of the "Body N" whose "Name" is @p name, or @p n_bodies if none is.
unsigned int body_number(ParameterHandler &prm, unsigned int n_bodies,
                         const std::string &name);

/**
 * The N of the "Body N" whose "Name" is @p name among the first @p n_bodies (read
 * from @p prm, at its top level); throws ExcBadInput naming @p owner (the scene entry
 * that refers to the body) if none is.
 */
unsigned int find_body(ParameterHandler &prm, unsigned int n_bodies,
                       const std::string &name, const std::string &owner);

/**
 * Sets @p entry ('Shape', or 'Prescribed velocity/Function expression') of the body
 * named @p body to @p value on behalf of scene entry @p owner. The file must leave
 * the entry at @p declared_default (or give @p value itself): a scene never silently
 * replaces what the user wrote, it throws ExcBadInput naming both entries instead.
 */
void set_body_entry(ParameterHandler &prm, unsigned int n_bodies, const std::string &body,
                    const std::string &entry, const std::string &value,
                    const std::string &declared_default, const std::string &owner);
/**
 * Sets @p entry (a path from the top level, 'Cracks/Polylines') to @p value on behalf
 * of scene entry @p owner, under the same rule as set_body_entry(); @p why is added
 * to the error message after the owner.
 */
void set_entry(ParameterHandler &prm, const std::string &entry, const std::string &value,
               const std::string &declared_default, const std::string &owner,
               const std::string &why = "");

/// Declares "Scene/Type" and every registered scene's entries in a subsection of
/// "Scene" named after it.
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
 * Its entries go into subsection "Scene/NAME".
 */
#define LME_MPM_REGISTER_SCENE(CLASS, NAME, DESCRIPTION)                                 \
  LME_MPM_REGISTER_PLUGIN_FOR_DIMS(::lme_mpm::SceneRegistry, scene, CLASS, NAME,         \
                                   DESCRIPTION,                                          \
                                   ::lme_mpm::PluginEntries::own_subsection)

#endif
