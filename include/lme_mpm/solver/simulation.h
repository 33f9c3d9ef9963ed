#ifndef LME_MPM_SOLVER_SIMULATION_H
#define LME_MPM_SOLVER_SIMULATION_H

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/parsed_function.h>
#include <deal.II/base/timer.h>

#include <lme_mpm/boundary/node_constraints.h>
#include <lme_mpm/fracture/crack_set.h>
#include <lme_mpm/fracture/fracture_model.h>
#include <lme_mpm/fracture/neighbourhood.h>
#include <lme_mpm/grid/background_grid.h>
#include <lme_mpm/materials/material.h>
#include <lme_mpm/output/particle_output.h>
#include <lme_mpm/particles/particle_store.h>
#include <lme_mpm/shape_functions/shape_function.h>
#include <lme_mpm/solver/explicit_newmark.h>

#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace lme_mpm
{
/// How many of each repeated subsection a parameter file declares (read first).
struct ParameterCounts
{
  unsigned int dim         = 2;
  unsigned int materials   = 1;
  unsigned int bodies      = 1;
  unsigned int constraints = 0;
  unsigned int probes      = 0;

  static void declare_parameters(ParameterHandler &prm);
  void parse_parameters(ParameterHandler &prm);
};

/// A run that became unphysical or unstable; the message says where and why.
DeclException5(ExcRunAborted, unsigned int, double, unsigned int, std::string,
               std::string, << "Run stopped at step " << arg1 << ", time " << arg2
                            << ": particle " << arg3 << " at " << arg4 << ": " << arg5);

/// A point where history.csv reports the stress averaged over nearby particles.
template <int dim>
struct Probe
{
  std::string name;
  Point<dim> point;
  double radius;
};

/**
 * One MPM run: reads a parameter file's entries, builds grid, particles, shape
 * functions, materials and constraints, and advances them with the explicit Newmark
 * predictor-corrector (doc/theory.md), writing VTU/PVD, history.csv and
 * summary.json to the output directory.
 */
template <int dim>
class Simulation
{
public:
  static void declare_parameters(ParameterHandler &prm, const ParameterCounts &counts);

  /// Parses and checks everything; throws naming the entry on bad input. Writes nothing.
  Simulation(ParameterHandler &prm, const ParameterCounts &counts,
             std::ostream &console = std::cout);

  /// Runs to the end time. Returns the summary values (also in summary.json).
  std::map<std::string, double> run();

  /// Advances one time step (public for tests).
  void step();

  double time() const { return t; }
  double time_step() const { return dt; }
  const ParticleStore<dim> &particles() const { return store; }
  const BackgroundGrid<dim> &grid() const { return background; }
  /**
   * Continues the run saved in @p directory/checkpoint.bin (written by a run of the same
   * parameter file); output goes on in that directory. Call before run().
   */
  void resume_from(const std::string &directory);

  /// A hash of every particle field and the time: equal states, equal sums (FNV-1a).
  std::uint64_t state_checksum();

  /// Kinetic, strain, external work and total energy (J) now.
  std::map<std::string, double> energies() const;

private:
  void setup_particles(ParameterHandler &prm, const ParameterCounts &counts);
  void setup_time_step(ParameterHandler &prm);
  void locate_and_sort();
  std::pair<unsigned int, unsigned int> support_reach(std::size_t begin,
                                                      std::size_t end) const;
  /// Calls f(p) for every particle, in an order that adds to each node in a way
  /// independent of the thread count (two colours of slabs of cell layers).
  template <class F>
  void scatter(const F &f);
  /// The same order, handing f(begin, end) chunks of at most scatter_chunk particles.
  template <class F>
  void scatter_chunks(const F &f);
  /// Small enough for a chunk's connectivity to stay in the L2 cache.
  static constexpr std::size_t scatter_chunk = 256;
  void write_output_row(bool final_row);
  void abort_run(std::size_t p, const std::string &why) const;
  void update_fracture();
  void write_checkpoint();
  /// Mx = M_C x with the consistent mass matrix (two transfers, no matrix stored).
  void apply_consistent_mass(const std::vector<Tensor<1, dim>> &x,
                             std::vector<Tensor<1, dim>> &Mx);
  template <class Constrain>
  void correct_towards_consistent_mass(std::vector<Tensor<1, dim>> &x,
                                       const std::vector<Tensor<1, dim>> &rhs,
                                       const Constrain &constrain);

  // Configuration.
  unsigned int verbosity;
  std::string output_directory;
  double end_time, output_interval, thickness;
  ExplicitNewmark newmark;
  Tensor<1, dim> body_force;
  double dt = 0, t = 0;
  unsigned int n_steps = 0, step_count = 0;
  double mass_tolerance = 0;
  // Checkpoints.
  unsigned int checkpoint_every_steps = 0;
  double checkpoint_every_seconds     = 0;
  bool resumed                        = false;
  std::uint64_t resumed_history_size  = 0;
  unsigned int mass_corrections       = 0;
  bool write_particles;
  unsigned int n_threads_used = 1;

  BackgroundGrid<dim> background;
  ParticleStore<dim> store;
  std::unique_ptr<ShapeFunction<dim>> shape_function;
  std::vector<std::unique_ptr<Material<dim>>> materials;
  /// Per material; null where the material does not fracture.
  std::vector<std::unique_ptr<FractureModel<dim>>> fracture_models;
  Neighbourhood<dim> neighbours;
  FractureFields fracture_fields;
  bool fracture_active = false;
  CrackSet<dim> cracks;
  // Farthest a support reaches (for the cracks' second fields) and the smallest
  // particle spacing of the bodies (for their growth).
  double crack_reach = 0, particle_spacing = std::numeric_limits<double>::max();
  // Per extra node: the crack faces there have closed (this step).
  std::vector<std::uint8_t> faces_closed;
  std::vector<Tensor<1, dim>> nodal_displacement;
  // Per particle: a node of its support has a second field (this step).
  std::vector<std::uint8_t> touches_crack;
  void crack_face_contact(std::vector<Tensor<1, dim>> &x,
                          const std::vector<Tensor<1, dim>> *rate);
  std::vector<std::unique_ptr<NodeConstraint<dim>>> constraints;
  std::vector<Probe<dim>> probes;
  unsigned int peak_constraint = numbers::invalid_unsigned_int, peak_component = 0;
  double peak_force = -std::numeric_limits<double>::max(), displacement_at_peak = 0;
  Connectivity<dim> conn;
  // How many cell layers the shape-function supports have reached below and above
  // their particles' layers so far (the slab width of the coloured scatter).
  unsigned int slab_below = 0, slab_above = 0;

  // Nodal fields (lexicographic node index).
  std::vector<double> nodal_mass;
  std::vector<Tensor<1, dim>> nodal_momentum, nodal_mass_acceleration, nodal_rate,
      nodal_force, nodal_acceleration;
  // Per-particle displacement increment of the current step.
  std::vector<Tensor<1, dim>> particle_increment;
  // Scratch for the consistent-mass corrections.
  std::vector<Tensor<1, dim>> nodal_rhs, nodal_scratch, particle_scratch;
  // Nodes that carry mass this step, ascending. Nodal loops run over them only and the
  // nodal arrays are zero elsewhere, so empty grid regions cost nothing per step.
  std::vector<unsigned int> active_nodes;
  /// Zeroes the nodal arrays where the last step wrote them (sizes them on first use).
  void clear_nodal_arrays();
  /// Collects the nodes with positive mass after the particle-to-grid transfer.
  void collect_active_nodes();
  /// Runs f(I) for every active node, in parallel.
  template <class F>
  void for_active_nodes(const F &f) const;

  // Energy accounting.
  double external_work = 0, initial_total_energy = 0;
  double max_energy_drift = 0, energy_scale = 0;

  // Exact solution (verification scenes).
  bool compare_exact = false;
  std::unique_ptr<Functions::ParsedFunction<dim>> exact_displacement, exact_velocity,
      exact_stress;
  double exact_stress_norm = 0, max_error_stress = 0;
  SymmetricTensor<2, dim> exact_stress_at(const Point<dim> &X) const;
  double exact_displacement_norm = 0, exact_velocity_norm = 0;
  double max_error_displacement = 0, max_error_velocity = 0;

  // Output.
  std::unique_ptr<ParticleOutput<dim>> output;
  std::ofstream history;
  double next_output_time = 0;
  std::ostream &console_stream;
  ConditionalOStream pcout;
  std::map<std::string, double> results;
};

/**
 * Reads a parameter file, applies "Subsection/Entry=value" overrides, builds the
 * simulation of the declared dimension and runs it. Throws on bad input before
 * anything is written.
 */
std::map<std::string, double>
run_parameter_file(const std::string &file, const std::vector<std::string> &overrides,
                   std::ostream &console = std::cout, const std::string &resume = "");

/// Applies "A/B/Entry=value" overrides; with @p skip_unknown, unknown entries are
/// ignored.
void apply_overrides(ParameterHandler &prm, const std::vector<std::string> &overrides,
                     bool skip_unknown);

/// Writes the documented default parameter file of a 2D run.
void print_default_parameters(std::ostream &out);
} // namespace lme_mpm

#endif
