#ifndef LME_MPM_FRACTURE_NEIGHBOURHOOD_H
#define LME_MPM_FRACTURE_NEIGHBOURHOOD_H

#include <deal.II/base/point.h>

#include <lme_mpm/base/dealii.h>
#include <lme_mpm/fracture/cell_search.h>
#include <lme_mpm/particles/particle_store.h>

#include <cstdint>
#include <functional>
#include <vector>

namespace lme_mpm
{
/**
 * The epsilon-neighbourhood of every particle: the particles within a radius,
 * itself included, in compressed rows. Given body ids, only particles of the
 * particle's own body are neighbours, so a platen, roller or hammer pressed against a
 * specimen does not enter the specimen's averages (nor the specimen the tool's); a
 * predicate can also cut pairs across explicit crack faces. Built in linear time from
 * the store's own order: the particles are sorted by background cell, so each
 * particle looks only at the particles of the cells within the radius (CellSearch),
 * and visiting those cells in increasing index gives every row in increasing particle
 * index without a sort (the order the models sum in, whatever the thread count).
 *
 * Rows can be limited to the particles within the radius of a few seed particles
 * (those where a fracture criterion can trigger) and, among them, to those that take a
 * row (those a model reads): the others get empty rows, and when there is no seed the
 * build costs one scan of the flags.
 */
template <int dim>
class Neighbourhood
{
public:
  /// Bits of the @p seeds argument of build().
  enum Flags : std::uint8_t
  {
    seed      = 1, ///< the particles within the radius of this one get their rows
    takes_row = 2  ///< this particle gets its row if a seed is within the radius
  };

  /**
   * Rebuilds the lists for the particles of @p store, which must be sorted by the
   * cells of @p grid (ParticleStore::sort_by_cell() after their cells were located),
   * with search radius @p radius. Pairs of different bodies are left out, and so are
   * pairs (p, q) for which @p separated returns true (for example the two faces of an
   * explicit crack). With @p seeds (Flags per particle), only the particles flagged
   * takes_row within @p radius of one flagged seed (of any body, on either side of a
   * crack) get their row; the others get an empty one. With @p may_be_separated,
   * @p separated is asked only for the pairs of particles p for which
   * may_be_separated(p) is true (those near a crack face), once per row.
   */
  void build(const ParticleStore<dim> &store, const BackgroundGrid<dim> &grid,
             double radius,
             const std::function<bool(std::size_t, std::size_t)> &separated = {},
             const std::vector<std::uint8_t> *seeds                         = nullptr,
             const std::function<bool(std::size_t)> &may_be_separated       = {});

  /// The number of particles.
  std::size_t size() const { return offsets.empty() ? 0 : offsets.size() - 1; }
  /// The neighbours of particle @p p, in increasing order: [begin(p), end(p)).
  const std::uint32_t *begin(const std::size_t p) const
  {
    return list.data() + offsets[p];
  }
  const std::uint32_t *end(const std::size_t p) const { return list.data() + ends[p]; }
  /// The total length of the lists.
  std::size_t n_pairs() const { return pairs; }
  /// Whether particle @p p has its row (a row holds the particle itself, so it is
  /// never empty); without seeds every particle has one.
  bool has_row(const std::size_t p) const { return ends[p] > offsets[p]; }
  /// The number of particles with a row.
  std::size_t n_rows() const { return rows; }

private:
  /// Flags in `wanted` the particles that take a row and lie within the radius of a
  /// seed; cells that hold no seed are skipped without looking at their particles.
  void mark_rows_near_seeds(const ParticleStore<dim> &store, const CellSearch<dim> &cells,
                            double radius, const std::vector<std::uint8_t> &seeds);
  /**
   * Fills the rows of the wanted particles with the neighbours that same(p, q)
   * accepts, in increasing index. With @p roomy, every row gets room for all the
   * particles of the cells within the radius, so one pass over the candidates fills it
   * (the distance and crack tests are the cost); otherwise (every particle has a row,
   * and that room would be about 2 (2D) or 3.2 (3D) times the rows, at a radius of 1.5
   * cells and 2 particles per cell direction) a counting pass sizes them exactly.
   */
  template <class Same>
  void fill_rows(const ParticleStore<dim> &store, const CellSearch<dim> &cells,
                 double radius, const Same &same, bool roomy);

  // Row p is list[offsets[p], ends[p]); a row may have room beyond its end.
  std::vector<std::size_t> offsets, ends;
  std::vector<std::uint32_t> list;
  // Scratch, kept between builds.
  std::vector<std::uint8_t> seeded, near_seeds, wanted, cut;
  std::size_t rows = 0, pairs = 0;
};
} // namespace lme_mpm

#endif
