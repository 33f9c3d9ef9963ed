#ifndef LME_MPM_DISTRIBUTED_HALO_H
#define LME_MPM_DISTRIBUTED_HALO_H

#include <lme_mpm/base/dealii.h>
#include <lme_mpm/grid/background_grid.h>

#include <array>
#include <cstdint>
#include <vector>

namespace lme_mpm
{
/**
 * How far one step of a particle reads, in the lengths of the grid where it is: what
 * a distributed run's halo is built from. On a graded grid the reach shrinks with the
 * cells, so a halo in the fine cells is as many fine cells wide as a halo in the
 * coarse cells is coarse ones.
 */
struct HaloReach
{
  /// Per grid node: how far from it the particles it couples to lie (m).
  std::vector<double> node_radius;
  /// Particle-node-particle passes: each reads the nodes within node_radius of the
  /// particles read so far, then the particles within node_radius of those nodes.
  unsigned int support_passes = 0;
  /// Per cell (empty: none): how far a particle there reads other particles directly
  /// (fracture neighbourhood and crack band), m; the farther of the two particles'
  /// reaches counts.
  std::vector<double> cell_radius;
  /// Cells added all round: particles crossing cells within a step.
  unsigned int margin_cells = 2;
};

/// Cells [lo[d], hi[d]) along each direction d of a grid.
template <int dim>
struct CellBox
{
  std::array<unsigned int, dim> lo, hi;
};

/**
 * The cells a set of cells reads through a HaloReach, on the cells of a background
 * grid (masks of one byte per cell in the grid's lexicographic order). Every query
 * costs O(cells): boxes of cells are flagged and tested with summed-area tables, so
 * halos of any width cost the same. Knows nothing of ranks, so it is tested on one.
 */
template <int dim>
class HaloCells
{
public:
  /// Boxes for dilate() and cells_within() only.
  explicit HaloCells(const BackgroundGrid<dim> &grid);
  /// Boxes for reached() too: each node's support box and each cell's fracture box,
  /// computed once.
  HaloCells(const BackgroundGrid<dim> &grid, const HaloReach &reach);

  /**
   * The cells the particles in the cells flagged in @p mask read in one step: support
   * passes first, then the direct particle reach (both ways: a cell reaching a flagged
   * one, and every cell a flagged one reaches), then the margin.
   */
  std::vector<std::uint8_t> reached(const std::vector<std::uint8_t> &mask) const;
  /// Cells within @p k[d] cells (along each d) of a cell flagged in @p mask.
  std::vector<std::uint8_t> dilate(const std::vector<std::uint8_t> &mask,
                                   const std::array<unsigned int, dim> &k) const;
  /// Cells per direction that cover a distance @p width from anywhere in a cell.
  std::array<unsigned int, dim> cells_within(double width) const;

private:
  std::array<unsigned int, dim> cells_per_direction() const;

  const BackgroundGrid<dim> &grid;
  HaloReach reach;
  /// Per node: the cells within its support radius; per cell: within its reach.
  std::vector<CellBox<dim>> node_box, cell_box;
};
} // namespace lme_mpm

#endif
