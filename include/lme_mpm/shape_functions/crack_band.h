#ifndef LME_MPM_SHAPE_FUNCTIONS_CRACK_BAND_H
#define LME_MPM_SHAPE_FUNCTIONS_CRACK_BAND_H

#include <lme_mpm/grid/background_grid.h>
#include <lme_mpm/shape_functions/shape_function.h>

#include <utility>
#include <vector>

namespace lme_mpm
{
/**
 * Width, in cells, of the band a crack localises in with these shape functions, for
 * particles placed at @p offsets (their positions within a cell along each direction,
 * in [0, 1]) with volumes of @p weights (fractions of the cell along each direction;
 * times @p thickness in 2D), as functions with a particle domain need them.
 *
 * A crack on the grid is a jump of the nodal displacements between two node planes. The
 * particles then strain by jump x g(x), where g(x) = sum over the nodes beyond the jump
 * of dN_a/dn, the functions' step response; its integral across the band is 1 whatever
 * the functions. The band's traction follows the particles that strain most, so the
 * opening they see, h_b g_max x jump, is the band's opening exactly when h_b = 1 / g_max:
 * that width makes a crack band of eigensoftening dissipate G_F per unit area. Linear
 * functions give one cell; smoother ones spread the jump (LME with gamma = 1.8, about 1.3
 * cells at two Gauss points per cell; cubic B-splines 1.5), and a band of one cell would
 * then dissipate that many times G_F (doc/validation.md, "Tension bar").
 *
 * Evaluated numerically on @p grid with the functions themselves, so a plug-in shape
 * function gets its own width: for each direction with at least two cells, the jump
 * between the two node planes of the middle cell, g at every particle position of that
 * cell (width), and at the particle positions of the three cells on either side
 * (reach); the result is the mean over those directions. Throws
 * ExcShapeFunctionFailure if the functions cannot be evaluated there.
 */
/// The band a crack localises in with a family of shape functions (crack_band()).
struct CrackBand
{
  /// 1 / (h g_max): the band width, in cells, a crack band uses
  double width_cells = 1;
  /// How far (in cells) from the most strained particles the jump still strains a
  /// particle by at least 1 % as much: 0 for linear functions, whose jump strains
  /// only the particles of its own cell, all alike
  double reach_cells = 0;
};

template <int dim>
CrackBand crack_band(const ShapeFunction<dim> &functions, const BackgroundGrid<dim> &grid,
                     const std::vector<double> &offsets,
                     const std::vector<double> &weights, double thickness);
/// Particle positions and volume shares in a cell along each direction (crack_band()).
using CellPlacement = std::pair<std::vector<double>, std::vector<double>>;

/// crack_band() for each of @p placements; equal placements share one evaluation.
template <int dim>
std::vector<CrackBand>
crack_bands(const ShapeFunction<dim> &functions, const BackgroundGrid<dim> &grid,
            const std::vector<CellPlacement> &placements, double thickness);
} // namespace lme_mpm

#endif
