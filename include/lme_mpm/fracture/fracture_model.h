#ifndef LME_MPM_FRACTURE_FRACTURE_MODEL_H
#define LME_MPM_FRACTURE_FRACTURE_MODEL_H

#include <deal.II/base/parameter_handler.h>

#include <lme_mpm/base/parameters.h>
#include <lme_mpm/base/registry.h>
#include <lme_mpm/fracture/neighbourhood.h>
#include <lme_mpm/particles/particle_store.h>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace lme_mpm
{
/// A snapshot of the particle fields fracture models read from neighbours, taken
/// before any particle changes state in the step (so the update is order-free).
struct FractureFields
{
  std::vector<double> max_principal_stress; ///< of the undamaged stress; 0 once failed
  std::vector<double> energy_density;       ///< sigma : eps / 2 (J/m^3); 0 once failed
  /// Local grid spacing h of each particle (m), the length of eps = C_eps h and of a
  /// band width tied to the grid: the smallest side of the cell that held the particle
  /// at t = 0 (fixed, so a particle keeps its lengths as it moves). Empty on a uniform
  /// grid, where every particle's h is FractureContext::grid_spacing.
  std::vector<double> spacing;
  /// Per body: the width, in cells, of the band a crack localises in with the run's
  /// shape functions and that body's particle placement (crack_band()); a band width
  /// tied to the grid is this times the particle's spacing. Empty: 1 cell.
  std::vector<double> band_cells;
  /// Per body: how far, in cells, a crack's jump strains particles beside the most
  /// strained ones (crack_band()). Empty: 0.
  std::vector<double> band_reach;
  /// ParticleStore::crack_opening, kept once failed: the band's other particles read it
  std::vector<double> crack_opening;
  /// The crack strain of each particle: the part of its max principal strain its
  /// damage does not carry, damage times that strain (the whole strain once failed,
  /// 0 for an intact particle). Across a crack band it integrates to the opening.
  std::vector<double> crack_strain;
  /// The undamaged stress of each particle (0 once failed), its dim (dim + 1) / 2
  /// components xx, xy, (xz,) yy, (yz, zz) one after the other; filled only where a
  /// model reads it (FractureModel::reads_stress_tensors()).
  std::vector<double> stress;
  /// 1 for a particle with an oriented crack (crack-oriented damage), whose stress
  /// follows its crack's law, not the elastic field; filled with `stress`. Taken
  /// before the step's update, so a crack that opens in it does not depend on the
  /// order the particles are visited in.
  std::vector<std::uint8_t> cracked;

  double spacing_of(const std::size_t p, const double uniform_spacing) const
  {
    return spacing.empty() ? uniform_spacing : spacing[p];
  }
  double band_cells_of(const unsigned int body) const
  {
    return body < band_cells.size() ? band_cells[body] : 1.0;
  }
  double band_reach_of(const unsigned int body) const
  {
    return body < band_reach.size() ? band_reach[body] : 0.0;
  }
};

/**
 * Where a fracture model can act on a particle that has not started to fracture: only
 * if a particle of its epsilon-neighbourhood has a snapshot field above a threshold
 * (an average over the neighbourhood exceeds a bound only if some member does). The
 * coupling then builds neighbourhood rows only around such particles, which before
 * fracture starts is none at all.
 */
struct FractureTrigger
{
  enum class Field
  {
    none, ///< no bound: every particle gets its row every step
    max_principal_stress,
    energy_density
  };
  Field field      = Field::none;
  double threshold = 0; ///< in the field's units
};

/// What a fracture model is built with.
struct FractureContext
{
  double grid_spacing   = 0; ///< smallest spacing of the grid (h of a uniform grid)
  double thickness      = 1; ///< 2D thickness, for the particle spacing
  unsigned int dim      = 2;
  double p_wave_modulus = 0; ///< rho c_P^2 of the material, for sanity checks
  /// lambda / M of the material (the stress across a uniaxial strain over the stress
  /// along it, as the material gives them): how the normal stress across a crack
  /// pulls on the stress parallel to it (crack-oriented damage).
  double lame_coupling = 0;
  std::string section; ///< "Material N/Fracture", for messages
};

/**
 * A fracture model acting on the particles of one material through their
 * epsilon-neighbourhood: it may set damage, onset data, failure and the dissipated
 * energy of the particles in a range, reading neighbours only through
 * FractureFields. One virtual call per block of particles.
 */
template <int dim>
class FractureModel
{
public:
  virtual ~FractureModel()         = default;
  virtual std::string name() const = 0;
  /// Radius of the epsilon-neighbourhood (m) of a particle whose local grid spacing
  /// (FractureFields::spacing) is @p h.
  virtual double epsilon(double h) const = 0;
  /// How far from a particle its neighbours are searched (m), at least epsilon(@p h).
  virtual double search_radius(const double h) const { return epsilon(h); }
  virtual void update(ParticleStore<dim> &particles, const Neighbourhood<dim> &neighbours,
                      const FractureFields &fields, std::size_t begin, std::size_t end,
                      unsigned int material_id) const = 0;
  /**
   * The model's trigger for neighbourhoods searched to the radius epsilon(@p
   * h_largest). A model that gives one reads the row of a particle only where
   * Neighbourhood::has_row() is true: a particle without a row has failed, or has no
   * neighbour whose field exceeds the threshold. The default, no trigger, gives every
   * particle a row.
   */
  virtual FractureTrigger trigger(double /*h_largest*/) const { return {}; }
  /// Counters for summary.json.
  virtual std::vector<std::pair<std::string, double>> statistics() const { return {}; }
  /// True if update() reads FractureFields::crack_strain (the coupling computes it
  /// only then).
  virtual bool reads_crack_strains() const { return false; }
  /// True if update() reads FractureFields::stress (the coupling copies it only then).
  virtual bool reads_stress_tensors() const { return false; }
  /// True if update() scales the strength by ParticleStore::strength (the models that
  /// a 'Strength variability' can apply to).
  virtual bool reads_strength_factors() const { return false; }
  /**
   * True if update() keeps, of each row, only the neighbours within its own radius
   * (at most Neighbourhood::radius()) by testing their distance itself. The coupling
   * then keeps the rows across steps with a skin (Neighbourhood::keep_lists()): a row
   * may also hold particles a little beyond the radius. With the default, false, the
   * rows are made anew every step and hold the particles within the radius only.
   */
  virtual bool reads_rows_with_skin() const { return false; }
  /**
   * The farthest (m) update() reads in the row of a particle whose own spacing is
   * @p h, in a body whose crack band reaches @p band_reach_cells cells
   * (FractureFields::band_reach_of()). On a graded grid the rows are searched to the
   * radius of the widest cell; a finite answer lets the coupling cut each particle's
   * row to its own reach, which gives the same sums where the model tests the
   * distances itself. The default, infinity: every row reaches the search radius.
   */
  virtual double row_reach(const double /*h*/, const double /*band_reach_cells*/) const
  {
    return std::numeric_limits<double>::infinity();
  }
};

template <int dim>
using FractureModelRegistry = Registry<FractureModel<dim>, FractureContext>;

/**
 * The entries of "Material N/Fracture" that more than one model reads: the
 * neighbourhood's size and the fracture energy, with their checks.
 */
struct SharedFractureEntries
{
  double epsilon_factor = 2, fracture_energy = 100;
  void entries(EntryList &list);
  /// Reads them from @p prm (in "Material N/Fracture", named @p section in messages)
  /// and checks them; throws ExcBadInput naming the entry.
  static SharedFractureEntries parse(dealii::ParameterHandler &prm,
                                     const std::string &section);
};

/**
 * Entries of "Material N/Fracture" that more than one model reads ("Epsilon factor",
 * "Fracture energy"). Each such model calls it from its own declare_parameters, so
 * these entries are declared once per model: deal.II lets an entry be declared again,
 * the later declaration replacing the value (back to the default), default,
 * documentation and pattern of the earlier one. As all of them come from this one
 * function, the repeats change nothing; declare_fracture_parameters() calls it once
 * more after the models so that these entries are this function's whatever a plug-in
 * declared under the same names. Call before parsing, like every declaration.
 */
void declare_shared_fracture_parameters(dealii::ParameterHandler &prm);

/**
 * Declares everything in "Material N/Fracture"; call it inside that subsection: the
 * "Model" selection (none or a registered model) and every registered model's
 * entries, which its static declare_parameters puts straight into the subsection.
 */
template <int dim>
void declare_fracture_parameters(dealii::ParameterHandler &prm);
} // namespace lme_mpm

/**
 * Registers fracture model class template CLASS (templated on dim, constructed from
 * (ParameterHandler &, const FractureContext &)) under NAME for dim = 2 and 3. A
 * static declare_parameters(ParameterHandler &), if it has one, declares its entries
 * straight into "Material N/Fracture".
 */
#define LME_MPM_REGISTER_FRACTURE_MODEL(CLASS, NAME, DESCRIPTION)                        \
  LME_MPM_REGISTER_PLUGIN_FOR_DIMS(::lme_mpm::FractureModelRegistry, fracture_model,     \
                                   CLASS, NAME, DESCRIPTION,                             \
                                   ::lme_mpm::PluginEntries::caller_subsection)

#endif
