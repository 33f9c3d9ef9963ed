#ifndef LME_MPM_FRACTURE_CRACK_SET_H
#define LME_MPM_FRACTURE_CRACK_SET_H

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <lme_mpm/base/dealii.h>
#include <lme_mpm/grid/background_grid.h>
#include <lme_mpm/grid/field_layout.h>
#include <lme_mpm/particles/particle_store.h>
#include <lme_mpm/shape_functions/shape_function.h>

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

namespace lme_mpm
{
/**
 * Explicit cracks (polylines, 2D) that split the grid's velocity field: a grid node
 * near a crack carries a second field, and a particle whose straight line to the node
 * crosses a crack talks to that second field instead of the first (Nairn's CRAMP).
 * The two faces of a crack then move independently even where one node's support
 * spans both, which a single-valued field cannot do: a notch narrower than the
 * support is otherwise bridged by the nodes the faces share.
 *
 * The second fields are extra node indices past the grid's own, so every nodal loop
 * handles them unchanged; remapping happens in the connectivity right after the
 * shape functions are computed. A crack may grow with eroded particles: its tips
 * follow the failed particles just ahead of them. Faces that close on each other are
 * kept from interpenetrating by a frictionless contact on the pair of fields.
 *
 * Cracks are fixed in space: the solver is small-strain, and a crack that moved with
 * the nodal velocity would follow the eroded particles (no stress, but still mass)
 * that drift in the opened gap. A body that moves further than a fraction of a cell
 * needs cracks that follow the material (roadmap, with the multi-body contact).
 */
template <int dim>
class CrackSet
{
public:
  static void declare_parameters(ParameterHandler &prm);
  /// Reads the "Cracks" subsection; explicit cracks exist in 2D only. "Cracks/Body"
  /// must be one of the @p n_bodies.
  void parse_parameters(ParameterHandler &prm, unsigned int n_bodies = 1);

  bool empty() const { return lines.empty(); }
  const std::vector<std::vector<Point<dim>>> &polylines() const { return lines; }
  bool face_contact() const { return contact; }
  /// The (0-based) body the cracks cut; other bodies' particles keep their fields.
  unsigned int body() const { return cracked_body; }

  /**
   * Gives a second field, tagged FieldLayout::crack_side in @p layout, to every node
   * within @p reach of a crack (the farthest a support reaches), keeping those it
   * already had.
   */
  void assign_fields(const BackgroundGrid<dim> &grid, double reach, FieldLayout &layout);
  /// The crack node index J of grid node @p I, or invalid_unsigned_int.
  unsigned int crack_node(const unsigned int I) const
  {
    return I < second.size() ? second[I] : numbers::invalid_unsigned_int;
  }
  /// How many nodes carry a crack's second field.
  unsigned int n_crack_nodes() const { return extra_primary.size(); }
  /// For crack node J (0-based): its grid node, its second field, and the unit
  /// normal pointing from the node's own side of the crack to the other.
  unsigned int primary_of(const unsigned int J) const { return extra_primary[J]; }
  unsigned int field_of(const unsigned int J) const { return extra_field[J]; }
  const Tensor<1, dim> &normal_of(const unsigned int J) const { return extra_normal[J]; }
  /// Sends the particle-node pairs of [begin, end) of the cracked body that cross a
  /// crack to the second fields, and sets touched[p] to 1 for such a particle with a
  /// node that has one (0 otherwise). Pure function of positions and connectivity:
  /// thread-safe per range.
  void separate(const ParticleStore<dim> &particles, const BackgroundGrid<dim> &grid,
                Connectivity<dim> &conn, std::size_t begin, std::size_t end,
                std::uint8_t *touched) const;

  /**
   * Extends the growing tips along the failed particles ahead of them: within 2.5
   * particle spacings and 45 degrees of the tip's direction (taken over the last five
   * spacings of the crack), the most straight ahead first. Returns true if a crack
   * grew.
   */
  bool grow(const ParticleStore<dim> &particles, double particle_spacing);
  /// True if the cracks grow with erosion (and there are any).
  bool grows() const { return growing && !lines.empty(); }
  /// How far from a failed particle grow() looks for intact ones (m).
  static double growth_reach(const double particle_spacing)
  {
    return 2.5 * particle_spacing;
  }

  /// Replaces the lines by those of a checkpoint (the caller checks that the count
  /// is the parameter file's); call assign_fields() on a fresh layout afterwards.
  void restore(std::vector<std::vector<Point<dim>>> saved);

private:
  bool crosses(const Point<dim> &p, const Point<dim> &q, unsigned int node) const;
  void update_normals();

  std::vector<std::vector<Point<dim>>> lines;
  bool growing = true, contact = true;
  unsigned int cracked_body = 0;
  // Per grid node: its crack node index J (or invalid); per crack node: grid node,
  // second field, normal, and the crack segments (line, first point) within reach,
  // in compressed rows.
  std::vector<unsigned int> second;
  std::vector<unsigned int> extra_primary, extra_field;
  std::vector<Point<dim>> extra_point;
  std::vector<Tensor<1, dim>> extra_normal;
  std::vector<unsigned int> segment_offsets{0};
  std::vector<std::pair<unsigned int, unsigned int>> segments;
};

/**
 * The segments of a set of crack polylines binned in squares of a given side, to tell
 * quickly whether two points that close lie on different faces of a crack (the
 * epsilon-neighbourhood must not reach across one).
 */
template <int dim>
class CrackSegmentBins
{
public:
  /// Bins the segments of @p lines (kept by reference) for pairs at most @p radius
  /// apart. Call again whenever the lines change.
  void build(const std::vector<std::vector<Point<dim>>> &lines, double radius);
  /**
   * True if p and q (at most the radius apart) lie on different faces of a crack: the
   * straight line p -> q crosses a segment, and the path round either end of that
   * crack is longer than the radius. Near a tip the faces stay connected through the
   * material ahead of it (the diffraction rule of Organ, Fleming & Belytschko 1996),
   * so a particle at the tip keeps the neighbours an uncracked one would have.
   */
  bool separates(const Point<dim> &p, const Point<dim> &q) const;
  /**
   * False if no point q within the radius of @p p can be separated from it
   * (separates(p, q) is false for all of them): no segment lies in a bin that box
   * reaches. A particle far from every crack then skips the test for its pairs.
   */
  bool may_separate(const Point<dim> &p) const;

private:
  /// Whether f(bin) is true for a bin that the box [lo, hi] overlaps (asked in
  /// increasing bin index until one is).
  template <class F>
  bool any_bin_over(const Point<dim> &lo, const Point<dim> &hi, const F &f) const;

  const std::vector<std::vector<Point<dim>>> *lines = nullptr;
  Point<dim> lower;
  double side = 0;
  std::array<unsigned int, dim> n_bins{};
  std::vector<std::vector<std::pair<unsigned int, unsigned int>>> bins;
};
} // namespace lme_mpm

#endif
