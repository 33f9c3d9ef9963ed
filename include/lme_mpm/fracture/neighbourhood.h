#ifndef LME_MPM_FRACTURE_NEIGHBOURHOOD_H
#define LME_MPM_FRACTURE_NEIGHBOURHOOD_H

#include <deal.II/base/point.h>

#include <cstdint>
#include <functional>
#include <vector>

namespace lme_mpm
{
using namespace dealii;

/**
 * The epsilon-neighbourhood of every particle: the particles within a radius,
 * itself included, in compressed rows. Given body ids, only particles of the
 * particle's own body are neighbours, so a platen, roller or hammer pressed against a
 * specimen does not enter the specimen's averages (nor the specimen the tool's); a
 * predicate can also cut pairs across explicit crack faces. Built
 * in linear time by binning the particles into cubes as wide as the radius (a
 * cell-linked list), so each particle looks only at the 3^dim cubes around it. Rows
 * are sorted, so the result does not depend on the thread count.
 */
template <int dim>
class Neighbourhood
{
public:
  /**
   * Rebuilds the lists for @p positions with search radius @p radius; with @p body
   * (one id per particle), pairs of different bodies are left out while building, and
   * so are pairs (p, q) for which @p separated returns true (for example the two faces
   * of an explicit crack).
   */
  void build(const std::vector<Point<dim>> &positions, double radius,
             const std::vector<std::uint16_t> *body                         = nullptr,
             const std::function<bool(std::size_t, std::size_t)> &separated = {});

  /// The number of particles.
  std::size_t size() const { return offsets.empty() ? 0 : offsets.size() - 1; }
  /// The neighbours of particle @p p, in increasing order: [begin(p), end(p)).
  const std::uint32_t *begin(const std::size_t p) const { return &list[offsets[p]]; }
  const std::uint32_t *end(const std::size_t p) const { return &list[offsets[p + 1]]; }
  /// The total length of the lists.
  std::size_t n_pairs() const { return list.size(); }

private:
  std::vector<std::size_t> offsets;
  std::vector<std::uint32_t> list;
  // Binning scratch, kept between builds.
  std::vector<std::uint32_t> bin_of, bin_start, sorted;
};
} // namespace lme_mpm

#endif
