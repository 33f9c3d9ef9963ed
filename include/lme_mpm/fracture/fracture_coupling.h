#ifndef LME_MPM_FRACTURE_FRACTURE_COUPLING_H
#define LME_MPM_FRACTURE_FRACTURE_COUPLING_H

#include <deal.II/base/parameter_handler.h>

#include <lme_mpm/base/rank_reductions.h>
#include <lme_mpm/fracture/crack_set.h>
#include <lme_mpm/fracture/fracture_model.h>
#include <lme_mpm/fracture/neighbourhood.h>
#include <lme_mpm/fracture/strength_field.h>
#include <lme_mpm/geometry/particle_generator.h>
#include <lme_mpm/grid/background_grid.h>
#include <lme_mpm/materials/material_set.h>
#include <lme_mpm/particles/particle_store.h>
#include <lme_mpm/shape_functions/crack_band.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace lme_mpm
{
/**
 * Couples the fracture models to the particles: one model (or none) per material,
 * read from "Material N/Fracture"; each step it takes the snapshot of the fields
 * neighbours read, builds the epsilon-neighbourhood where a model can act (around
 * the particles above a model's trigger, FractureTrigger), and runs every model on
 * its material's particles. Runs after all stresses of the step are known.
 */
template <int dim>
class FractureCoupling
{
public:
  /// Declares "Material N/Fracture" for the @p n_materials materials.
  static void declare_parameters(ParameterHandler &prm, unsigned int n_materials);
  /**
   * Builds the models. The lengths tied to the grid (eps = C_eps h, a band width of 0)
   * use each particle's local spacing on @p grid (FractureFields::spacing); @p
   * thickness is the 2D thickness. The grid must outlive this object.
   */
  void parse_parameters(ParameterHandler &prm, const MaterialSet<dim> &materials,
                        const BackgroundGrid<dim> &grid, double thickness);

  /// Distributed runs: every rank searches neighbourhoods to the largest radius.
  void set_ranks(const RankReductions &r) { ranks = &r; }

  /**
   * How far one fracture update reaches from a particle: the widest neighbourhood
   * and crack band (m), for the width of a distributed run's halo.
   */
  double reach() const { return reach_at(grid->max_spacing()); }
  /// The same where the particles' spacing h (a cell's shortest side) is @p h.
  double reach_at(double h) const;

  /// True if any material fractures.
  bool active() const { return any_model; }
  bool fractures(const unsigned int material) const
  {
    return models[material] != nullptr;
  }
  /**
   * Throws unless the neighbourhood of @p material is at least as wide as the spacing
   * h / @p particles_per_cell of the particles @p body_section places, in every cell
   * the body occupies (@p occupied, per cell; null: every cell of the grid) (a
   * narrower one holds the particle alone, and the criterion would average nothing).
   */
  void check_neighbourhood(unsigned int material, unsigned int particles_per_cell,
                           const std::string &body_section,
                           const std::vector<std::uint8_t> *occupied = nullptr) const;

  /**
   * Registers the bodies in order: checks each material of @p body against its
   * particles' spacing (check_neighbourhood(), in the cells it occupies) and keeps
   * its particles' placement in a cell for set_crack_band().
   */
  void add_body(const BodyPlacement &body);

  /**
   * The band a crack localises in, per body: crack_band() of the run's shape functions
   * @p functions for the body's particle placement (add_body()), its width and its
   * reach in cells; lengths tied to the grid are these times the particle's local
   * spacing. Without a fracturing material nothing is evaluated.
   */
  void set_crack_band(const ShapeFunction<dim> &functions);

  /**
   * Sizes the snapshot for @p particles; call before take_snapshot() in each step
   * (cheap after the first call). The first call sets the particles' strength
   * factors (ParticleStore::strength) from the materials' strength fields.
   */
  void prepare(ParticleStore<dim> &particles);
  /**
   * The snapshot of particles [@p begin, @p end), from their stresses and strains of
   * the step: called by the stress pass chunk by chunk, while the particles are in
   * cache. Thread-safe for disjoint ranges.
   */
  void take_snapshot(const ParticleStore<dim> &particles, std::size_t begin,
                     std::size_t end);

  /**
   * The fracture update of one step, after the stresses. With @p cracks, particles
   * on different faces of an explicit crack are not neighbours. @p snapshot_taken:
   * prepare() and take_snapshot() covered every particle since the stresses changed;
   * otherwise the update takes the snapshot itself.
   */
  void update(ParticleStore<dim> &particles, const CrackSet<dim> *cracks = nullptr,
              bool snapshot_taken = false);

  /// Counters of every model, and the failed particles and dissipated energy.
  void add_statistics(const ParticleStore<dim> &particles,
                      std::map<std::string, double> &results) const;

private:
  /// Sets every particle's strength factor from its material's field, and the floors.
  void assign_strengths(ParticleStore<dim> &store);
  /// Fills each particle's cell size (FractureFields::spacing) on a graded grid;
  /// returns the largest (the grid's smallest on a uniform one).
  double update_spacings(const ParticleStore<dim> &store);
  /// Fills row_reaches from the spacings, or empties it where the rows stay whole.
  void update_row_reaches(const ParticleStore<dim> &store);

  std::vector<std::unique_ptr<FractureModel<dim>>> models; ///< per material, or null
  std::vector<StrengthField<dim>> strength_fields;         ///< per material
  /// Per material, the smallest strength factor of its particles (its trigger is
  /// lowered by it); set, with the particles' factors, by the first prepare().
  std::vector<double> strength_floor;
  bool strengths_assigned         = false;
  bool any_model                  = false;
  const BackgroundGrid<dim> *grid = nullptr;
  double specimen_thickness       = 1; ///< 2D
  /// Per body: its particles' positions and volume shares in a cell (add_body())
  std::vector<CellPlacement> placements;
  bool uniform_grid = true;
  Neighbourhood<dim> neighbours;
  CrackSegmentBins<dim> crack_bins;
  FractureFields fields;

  // Set by prepare() for the particles' count (spacings are of the reference
  // positions, so they hold for the whole run).
  static constexpr std::size_t unprepared = static_cast<std::size_t>(-1);
  std::size_t prepared_size               = unprepared;
  std::uint64_t prepared_version          = 0;
  std::vector<double> spacing_scratch; ///< room for the reordered spacings
  /// Each particle's row reach (FractureModel::row_reach()) on a graded grid where
  /// every model gives one (Neighbourhood::cut_rows_to()); empty otherwise.
  std::vector<double> row_reaches;
  const RankReductions *ranks = nullptr;
  /// The largest spacing of any rank's particles (negative until the first prepare()).
  double h_all_ranks = -1;
  double radius      = 0; ///< of the neighbourhood search
  /// The neighbourhood's skin over its radius, where the models allow one.
  static constexpr double skin_fraction = 0.1;
  /// Without a model that gives no trigger: rows only around the seeds.
  bool seeded_rows = false;
  /// A body's crack band reaches beyond its own cell: softening particles then read
  /// their rows every step (the band shares its opening).
  bool shares_openings = false;
  /// A model measures its band from the neighbours' crack strains (the snapshot then
  /// holds them).
  bool measures_bands = false, reads_stresses = false;
  /// Threshold per field (FractureTrigger::Field), the lowest of the models'.
  std::array<double, 3> thresholds{};
  std::vector<std::uint8_t> seeds; ///< particles above a threshold
  // Rows built, and steps, for summary.json.
  double rows_built = 0, updates = 0;
};
} // namespace lme_mpm

#endif
