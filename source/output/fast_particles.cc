#include <lme_mpm/output/fast_particles.h>

#include <algorithm>
#include <limits>
#include <sstream>

namespace lme_mpm
{
template <int dim>
double FastParticles::transit_length(const ParticleStore<dim> &p,
                                     const std::vector<std::uint8_t> &prescribed)
{
  std::vector<Point<dim>> lo(prescribed.size()), hi(prescribed.size());
  std::vector<bool> seen(prescribed.size(), false);
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    const unsigned int b = p.body_id[i];
    for (unsigned int d = 0; d < dim; ++d)
    {
      lo[b][d] = seen[b] ? std::min(lo[b][d], p.position[i][d]) : p.position[i][d];
      hi[b][d] = seen[b] ? std::max(hi[b][d], p.position[i][d]) : p.position[i][d];
    }
    seen[b] = true;
  }
  double length = 0;
  for (unsigned int b = 0; b < lo.size(); ++b)
    if (seen[b] && prescribed[b] == 0)
      length = std::max(length, lo[b].distance(hi[b]));
  return length;
}

template double FastParticles::transit_length(const ParticleStore<2> &,
                                              const std::vector<std::uint8_t> &);
template double FastParticles::transit_length(const ParticleStore<3> &,
                                              const std::vector<std::uint8_t> &);

double FastParticles::warning_level(const std::string &family)
{
  // The largest level at which the vibrating bar (three periods, CFL 0.3 with the
  // travel limit, 40 and 160 cells) stayed within 1 % of its energy, rounded up to
  // two digits; the next level measured drifted by more (doc/stability.md, "Fast
  // particles on linear and uGIMP functions", benchmarks/fast_particle_levels.sh).
  if (family == "linear")
    return 0.31;
  if (family == "ugimp")
    return 3.8;
  return std::numeric_limits<double>::infinity();
}

void FastParticles::set_up(const std::string &f, const double h_min, const double c_P,
                           const double transit_length)
{
  family          = f;
  cells_per_speed = transit_length / (c_P * h_min);
  level           = warning_level(f);
}

bool FastParticles::observe(const double max_speed)
{
  const double m = max_speed * cells_per_speed;
  row_max        = std::max(row_max, m);
  run_max        = std::max(run_max, m);
  if (passed_at > 0 || !(m > level))
    return false;
  passed_at = m;
  return true;
}

void FastParticles::write_header(std::ostream &out) const
{
  out << ",fast_particle_cells";
}

void FastParticles::write_row(std::ostream &out)
{
  out << ',' << row_max;
  row_max = 0;
}

std::string FastParticles::warning() const
{
  if (!(passed_at > 0))
    return "";
  std::ostringstream s;
  s << "fast particles: the fastest particle covers " << passed_at
    << " cells while a P-wave crosses the largest body (history column "
       "fast_particle_cells); '"
    << family << "' shape functions were measured to hold the energy within 1 % up to "
    << level
    << " and to drift by more above it (doc/stability.md): expect energy gained or "
       "lost at cell crossings; 'Shape functions/Type' = bspline or lme does not have "
       "this error";
  return s.str();
}
} // namespace lme_mpm
