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
 *
 * With keep_lists(skin), the lists outlive a build, as the Verlet lists of molecular
 * dynamics do: a listed row holds every particle within radius + skin when the lists
 * were made, so it holds every particle within the radius until some particle has
 * moved half the skin. A build then only marks the rows wanted this step; it follows
 * a reorder of the store through its permutation (ParticleStore::sort_permutation()),
 * and makes the lists anew when a particle has moved too far or a wanted row has no
 * list. A store changed otherwise between two builds (particles exchanged between
 * ranks, added or removed) gets rows without a skin at that build. Its rows then hold
 * particles up to radius + skin: the reader tests the distance
 * (FractureModel::reads_rows_with_skin()).
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

  /**
   * Keeps the lists across builds with a skin of @p skin (m; 0, the default, makes
   * every row anew at every build and holds the particles within the radius only).
   * Builds with an explicit crack's @p separated test make their rows anew whatever
   * the skin.
   */
  void keep_lists(double skin);

  /**
   * Cuts the row of each particle p to its own reach, @p radii[p] (at most the
   * build's radius; the row of a particle whose reach exceeds the radius stays at the
   * radius), or, with nullptr (the default), leaves every row at the radius. Which
   * rows are wanted still follows the radius. The reaches belong to the particles:
   * they must move with them through each sort and not change while the lists are
   * kept. The vector must outlive the builds that use it.
   */
  void cut_rows_to(const std::vector<double> *radii) { row_radii = radii; }

  /// The number of particles.
  std::size_t size() const { return ends.size(); }
  /// The neighbours of particle @p p, in increasing order: [begin(p), end(p)). With
  /// a skin, they may lie up to radius() + skin from p.
  const std::uint32_t *begin(const std::size_t p) const
  {
    return list.data() + begins[p];
  }
  const std::uint32_t *end(const std::size_t p) const { return list.data() + ends[p]; }
  /// The total length of the rows of this build.
  std::size_t n_pairs() const { return pairs; }
  /// The radius of the last build.
  double radius() const { return search_radius; }
  /// How many times the lists were made (every build without a skin).
  std::size_t n_list_builds() const { return list_builds; }
  /// Whether particle @p p has its row (a row holds the particle itself, so it is
  /// never empty); without seeds every particle has one.
  bool has_row(const std::size_t p) const { return ends[p] > begins[p]; }
  /// The number of particles with a row.
  std::size_t n_rows() const { return rows; }

private:
  /// Flags in @p marked the particles that take a row and lie within @p radius of a
  /// seed; cells that hold no seed are skipped without looking at their particles.
  void mark_rows_near_seeds(const ParticleStore<dim> &store, const CellSearch<dim> &cells,
                            double radius, const std::vector<std::uint8_t> &seeds,
                            std::vector<std::uint8_t> &marked);
  /**
   * Fills the rows of the particles flagged in @p which with the neighbours within
   * their reach (@p radius, or the particle's own: cut_rows_to()) plus @p skin_added
   * that same(p, q) accepts, in increasing index, into `list` from
   * @p row_begins to @p row_ends. With @p roomy, every row gets room for all the
   * particles of the cells within the radius, so one pass over the candidates fills it
   * (the distance and crack tests are the cost); otherwise (every particle has a row,
   * and that room would be about 2 (2D) or 3.2 (3D) times the rows, at a radius of 1.5
   * cells and 2 particles per cell direction) a counting pass sizes them exactly.
   */
  template <class Same>
  void fill_rows(const ParticleStore<dim> &store, const CellSearch<dim> &cells,
                 double radius, double skin_added, const Same &same, bool roomy,
                 const std::vector<std::uint8_t> &which,
                 std::vector<std::size_t> &row_begins,
                 std::vector<std::size_t> &row_ends);
  /// Calls fill_rows() with the body and crack tests this build needs.
  void fill_rows_of(const ParticleStore<dim> &store, const CellSearch<dim> &cells,
                    double radius, double skin_added, bool roomy,
                    const std::vector<std::uint8_t> &which,
                    std::vector<std::size_t> &row_begins,
                    std::vector<std::size_t> &row_ends,
                    const std::function<bool(std::size_t, std::size_t)> &separated);
  /// Flags in `cut` the wanted rows whose pairs the crack test must see (all of them
  /// without @p may_be_separated; none without @p separated).
  void mark_cut_rows(const std::function<bool(std::size_t, std::size_t)> &separated,
                     const std::function<bool(std::size_t)> &may_be_separated);
  /// With a skin: carries the lists through the store's last reorder, or drops them
  /// when that cannot be done.
  void follow_order(const ParticleStore<dim> &store);
  /// With a skin: whether the kept lists hold every wanted row of this build.
  bool lists_hold(const ParticleStore<dim> &store, double radius) const;
  /// With a skin: the rows of this build from the kept lists; those an explicit crack
  /// may cut are copied behind the lists without the pairs it separates.
  void rows_from_lists(const ParticleStore<dim> &store, double radius,
                       const std::function<bool(std::size_t, std::size_t)> &separated,
                       const std::function<bool(std::size_t)> &may_be_separated);

  // Row p of this build is list[begins[p], ends[p]); a row may have room beyond its
  // end.
  std::vector<std::size_t> begins, ends;
  std::vector<std::uint32_t> list;
  double search_radius = 0;
  // Scratch, kept between builds.
  std::vector<std::uint8_t> near_seeds, wanted, cut;
  /// Each particle's own reach (cut_rows_to()), or nullptr.
  const std::vector<double> *row_radii = nullptr;
  /// The reach of particle @p p's row at a build of radius @p radius.
  double row_radius(const std::size_t p, const double radius) const
  {
    return row_radii ? std::min(radius, (*row_radii)[p]) : radius;
  }
  // The seeds' positions by cell: cell c's in [seed_begin[c], seed_begin[c + 1]).
  std::vector<std::size_t> seed_begin;
  std::vector<Point<dim>> seed_position;
  std::size_t rows = 0, pairs = 0, list_builds = 0;
  bool several_bodies = false;

  // Kept lists (skin > 0): the first kept_size entries of `list`, the row of a
  // `listed` particle p in [list_begins[p], list_ends[p]). They were made at
  // built_position, for the radius built_radius, without any crack test, and follow
  // the store's order built_version. Only particles of a body in listed_body enter
  // them.
  double skin                 = 0;
  bool lists_valid            = false;
  double built_radius         = 0;
  std::uint64_t built_version = 0;
  std::size_t kept_size       = 0;
  /// The store's order_version() at the last build (none yet: the largest value).
  std::uint64_t seen_version = static_cast<std::uint64_t>(-1);
  std::vector<std::size_t> list_begins, list_ends;
  std::vector<std::uint8_t> listed, listed_body;
  std::vector<Point<dim>> built_position;
  std::vector<std::uint32_t> inverse;
  // Scratch of follow_order(), kept between builds.
  std::vector<std::size_t> moved_begins, moved_ends;
  std::vector<std::uint8_t> moved_listed;
  std::vector<Point<dim>> moved_position;
};
} // namespace lme_mpm

#endif
