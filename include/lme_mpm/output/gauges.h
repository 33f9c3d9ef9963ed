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
 * of the particles whose reference position lies within the gauge's radius (its own,
 * or "Output/Gauge radius") of the point; in 3D a point given by x and y alone is a
 * line along z, which averages through the thickness. A clip gauge across a notch mouth
 * reads the crack mouth opening (CMOD); one across a disc's diameter its lateral
 * expansion. Particles of bodies that move as prescribed (rollers, platens) are not
 * gauged. history.csv gets opening_<name>; a loading servo (LoadingControl) may drive on
 * a gauge.
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
  /// "A (x, y), B (x, y), radius r m" of gauge @p g, for messages.
  std::string describe(unsigned int g) const;
  /// The particle mass within the radius of end @p end (0: A, 1: B) of gauge @p g, over
  /// this rank's particles.
  double mass_near(unsigned int g, unsigned int end, const ParticleStore<dim> &p) const
  {
    const auto s = sums(p);
    return s[4 * g + end];
  }

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
    double radius = 0;
    /// In 3D: A and B stand for lines along z (their z is 0 and ignored).
    bool line = false;
    /// Whether reference position @p x lies within the radius of point (or line) @p c.
    bool near(const Point<dim> &x, const Point<dim> &c) const
    {
      double d2 = 0;
      for (unsigned int d = 0; d < (line ? 2u : unsigned(dim)); ++d)
        d2 += (x[d] - c[d]) * (x[d] - c[d]);
      return d2 <= radius * radius;
    }
  };
  /// Per gauge and end: mass, then mass-weighted displacement along the gauge.
  std::vector<double> sums(const ParticleStore<dim> &particles) const;

  std::vector<Gauge> gauges;
  double radius = 0;
  std::vector<std::uint8_t> excluded;
};
} // namespace lme_mpm

#endif
