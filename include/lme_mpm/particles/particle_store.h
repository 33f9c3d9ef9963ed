#ifndef LME_MPM_PARTICLES_PARTICLE_STORE_H
#define LME_MPM_PARTICLES_PARTICLE_STORE_H

#include <deal.II/base/point.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <lme_mpm/base/dealii.h>

#include <cstdint>
#include <type_traits>
#include <vector>

namespace lme_mpm
{
/**
 * The particles, one array per field (structure of arrays), kept sorted by the
 * background cell that holds them so that the grid transfers sweep memory in order
 * and the scatter can be split into independent slabs. Every field is listed once in
 * for_each_field(), which is what resizing and reordering go through: a new field
 * added there moves with its particle.
 */
template <int dim>
class ParticleStore
{
public:
  std::size_t size() const { return position.size(); }

  /// Appends one particle with zeroed state; returns its index.
  std::size_t add(const Point<dim> &x, double mass, double volume, unsigned int material,
                  unsigned int body);

  void resize(std::size_t n);

  /**
   * Per-particle state that only some runs use. A run keeps what its parts read and
   * drops the rest before its particles are made: dropped fields stay empty, are not
   * resized, sorted, sent to other ranks or checkpointed, and their readers see them as
   * empty (memory per particle: doc/performance.md, "Cost against size"). A new store
   * keeps everything.
   */
  struct OptionalState
  {
    /// lme_lambda, lme_position and lme_lambda_rate: the shape functions' warm start.
    bool shape_function = true;
    /// onset_strain, onset_stress, crack_opening, dissipated, strength, crack_normal
    /// and crack_coupling: what a fracture model writes (damage and failed stay, as
    /// every stress and output reads them).
    bool fracture = true;
  };
  /// Keeps the fields @p kept names (sized as the others, zeroed) and frees the rest.
  void keep_state(const OptionalState &kept);
  const OptionalState &kept_state() const { return optional; }
  /// Bytes of one particle over every field kept (what a message or checkpoint holds).
  std::size_t bytes_per_particle() const;

  /**
   * Sorts by `cell` (which the caller has filled) over @p n_cells cells, and by `id`
   * within a cell; fills cell_offsets() so that the particles of cell c are
   * [cell_offsets[c], cell_offsets[c+1]). Skips the reorder when already sorted.
   * Returns true if the order changed. The order depends on the particles only, not
   * on the order they came in: a rank holding a subset of the particles sums their
   * contributions to a node in the same order as one rank holding all of them.
   */
  bool sort_by_cell(unsigned int n_cells);
  const std::vector<std::size_t> &cell_offsets() const { return offsets; }
  /// Changes whenever particles are reordered, added or removed: per-particle caches
  /// kept outside the store are stale once it differs from the value they saw.
  std::uint64_t order_version() const { return version; }
  /// Records a change of order or size made by a caller (bumps order_version()).
  void mark_reordered() { ++version; }
  /**
   * The reorder of the last sort_by_cell() that changed the order: the particle now at
   * q was at sort_permutation()[q]. It describes the last change of order only while
   * order_version() == sorted_version(); a cache kept for the order before it
   * (version sorted_version() - 1) can follow it instead of being rebuilt.
   */
  const std::vector<std::uint32_t> &sort_permutation() const { return permutation; }
  std::uint64_t sorted_version() const { return sorted_at; }

  // Kinematics.
  std::vector<Point<dim>> position;
  std::vector<Point<dim>> reference_position; ///< position at t = 0
  std::vector<Tensor<1, dim>> velocity;
  std::vector<Tensor<1, dim>> acceleration;
  // Mass and volume (volume includes the 2D thickness, so masses are the specimen's).
  std::vector<double> mass;
  std::vector<double> volume;
  std::vector<double> initial_volume;
  std::vector<double> density;
  // Mechanics (small strain; stress is the undamaged one).
  std::vector<SymmetricTensor<2, dim>> strain;
  std::vector<SymmetricTensor<2, dim>> strain_increment;
  std::vector<SymmetricTensor<2, dim>> stress;
  // Identity.
  std::vector<std::uint32_t> id;
  std::vector<std::uint16_t> material_id;
  std::vector<std::uint16_t> body_id;
  std::vector<std::uint32_t> cell; ///< index of the background cell holding it
  // Shape-function state: the LME Lagrange multiplier at lme_position and its
  // derivative d lambda / d x there, which extrapolate a warm start for next step.
  std::vector<Tensor<1, dim>> lme_lambda;
  std::vector<Point<dim>> lme_position;
  std::vector<Tensor<2, dim>> lme_lambda_rate;
  // Fracture state.
  std::vector<double> damage;       ///< chi in [0, 1]
  std::vector<double> onset_strain; ///< principal strain at softening onset
  std::vector<double> onset_stress; ///< own max principal stress at onset
  /// Crack opening from the particle's own strain, as a fraction of its law's
  /// critical opening (eigensoftening's band shares it)
  std::vector<double> crack_opening;
  std::vector<double> dissipated; ///< fracture energy dissipated so far (J)
  /// Tensile strength over the material's 'Tensile strength' (1 unless the material
  /// has Strength variability), fixed at the start.
  std::vector<double> strength;
  /// 1 once fully failed: no stress with isotropic damage, no traction across its
  /// crack with crack-oriented damage
  std::vector<std::uint8_t> failed;
  /**
   * Crack-oriented damage (doc/theory.md): the unit normal of the particle's crack,
   * fixed at onset (zero: no crack, or isotropic damage, where `damage` scales the
   * whole stress), and the coupling lambda / M of its material (lambda the Lame
   * constant, M = lambda + 2 mu), which says how the normal stress across the crack
   * pulls on the stress parallel to it.
   */
  std::vector<Tensor<1, dim>> crack_normal;
  std::vector<double> crack_coupling;
  /// 1 for a copy of a particle another MPI rank owns (a ghost in this rank's halo):
  /// it takes part in the step so that the owned particles near the partition
  /// boundary see all their neighbours, but it is not output, summed or checked.
  std::vector<std::uint8_t> ghost;

  /// Calls f(vector) for every per-particle field kept (kept_state()).
  template <class F>
  void for_each_field(F &&f)
  {
    visit_fields([&](auto &field, bool) { f(field); }, false);
  }
  /**
   * Calls f(vector) for every per-particle field, dropped ones included (empty), in
   * the order for_each_field() visits the kept ones: what a checksum of the state reads
   * (through value_at()), so that dropping a field changes no checksum.
   */
  template <class F>
  void for_all_fields(F &&f)
  {
    visit_fields([&](auto &field, bool) { f(field); }, true);
  }
  /// Particle @p p's value of @p field, or dropped_value() if the run dropped it.
  template <class T>
  T value_at(const std::vector<T> &field, const std::size_t p) const
  {
    return field.empty() ? dropped_value(field) : field[p];
  }
  /// The value a dropped field stands for: what a kept one holds in a run that does not
  /// use it (zero; the strength factor 1).
  template <class T>
  T dropped_value(const std::vector<T> &field) const
  {
    if constexpr (std::is_same_v<T, double>)
      if (&field == &strength)
        return 1.0;
    return T();
  }

private:
  /// The one list of fields: f(vector, kept) for each kept one, and for the dropped
  /// ones too if @p all.
  template <class F>
  void visit_fields(F &&f, const bool all)
  {
    auto always = [&](auto &field) { f(field, true); };
    auto shape  = [&](auto &field)
    {
      if (optional.shape_function || all)
        f(field, optional.shape_function);
    };
    auto fracture = [&](auto &field)
    {
      if (optional.fracture || all)
        f(field, optional.fracture);
    };
    always(position), always(reference_position), always(velocity), always(acceleration),
        always(mass), always(volume), always(initial_volume), always(density),
        always(strain), always(strain_increment), always(stress), always(id),
        always(material_id), always(body_id), always(cell);
    shape(lme_lambda), shape(lme_position), shape(lme_lambda_rate);
    always(damage);
    fracture(onset_strain), fracture(onset_stress), fracture(crack_opening),
        fracture(dissipated), fracture(strength);
    always(failed);
    fracture(crack_normal), fracture(crack_coupling);
    always(ghost);
  }

  OptionalState optional;
  std::vector<std::size_t> offsets;
  std::vector<std::uint32_t> permutation;
  std::uint64_t version = 0;
  /// order_version() after the last reordering sort (none yet: no version).
  std::uint64_t sorted_at = static_cast<std::uint64_t>(-1);
};

} // namespace lme_mpm

#endif
