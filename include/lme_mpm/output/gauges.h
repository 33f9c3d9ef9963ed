#ifndef LME_MPM_OUTPUT_GAUGES_H
#define LME_MPM_OUTPUT_GAUGES_H

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <lme_mpm/base/archive.h>
#include <lme_mpm/base/rank_reductions.h>
#include <lme_mpm/particles/particle_store.h>

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace lme_mpm
{
/**
 * Opening gauges ("Output/Opening gauges"): each a pair of material points A and B,
 * given by their positions at t = 0, and its reading the change in their distance,
 * (u_B - u_A) . (B - A) / |B - A|, where u is the mass-weighted mean displacement
 * of the particles whose reference position lies within "Output/Gauge radius" of the
 * point. A clip gauge across a notch mouth reads the crack mouth opening (CMOD); one
 * across a disc's diameter its lateral expansion. Particles of bodies that move as
 * prescribed (rollers, platens) are not gauged. history.csv gets opening_<name>; a
 * loading servo (LoadingControl) may drive on a gauge.
 */
template <int dim>
class OpeningGauges
{
public:
  static void declare_parameters(ParameterHandler &prm);
  /**
   * Reads the gauges; @p cell_size is the smallest cell, whose half is the radius
   * when the entry is 0. Throws ExcBadInput naming the entry for a malformed list, a
   * name used twice or two points closer than twice the radius.
   */
  void parse_parameters(ParameterHandler &prm, double cell_size);
  /// Which bodies are not gauged (1: prescribed).
  void set_excluded_bodies(const std::vector<std::uint8_t> &flags) { excluded = flags; }
  /**
   * Throws ExcBadInput naming the entry if a gauge point has no particle within the
   * radius (it would read zero); @p ranks sums over the ranks (null on one).
   */
  void check(const ParticleStore<dim> &particles, const RankReductions *ranks) const;

  bool empty() const { return gauges.empty(); }
  unsigned int size() const { return gauges.size(); }
  /// The index of the gauge named @p name, or size() if none.
  unsigned int find(const std::string &name) const;
  const std::string &name(unsigned int g) const { return gauges[g].name; }
  /// The names, comma separated (for messages).
  std::string names() const;

  /**
   * Every gauge's reading. Sums over this rank's own particles (not ghosts) and,
   * with @p ranks, over the ranks: every rank calls it together.
   */
  std::vector<double> read(const ParticleStore<dim> &particles,
                           const RankReductions *ranks) const;

  void write_header(std::ostream &out) const;
  /// One history row: every particle of the run (rank 0).
  void write_row(std::ostream &out, const ParticleStore<dim> &particles) const;

private:
  struct Gauge
  {
    std::string name;
    Point<dim> a, b;
  };
  /// Per gauge and end: mass, then mass-weighted displacement along the gauge.
  std::vector<double> sums(const ParticleStore<dim> &particles) const;

  std::vector<Gauge> gauges;
  double radius = 0;
  std::vector<std::uint8_t> excluded;
};
} // namespace lme_mpm

#endif
