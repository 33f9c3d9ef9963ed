#include <deal.II/base/symmetric_tensor.h>

#include <lme_mpm/base/input.h>
#include <lme_mpm/scenes/scene_tools.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <sstream>

namespace lme_mpm
{
namespace scenes
{
std::string number(const double x)
{
  std::ostringstream s;
  s.precision(15);
  s << x;
  return s.str();
}

void require_inside_grid(const EntryWriter &writer, const double x0, const double y0,
                         const double x1, const double y1, const std::string &owner,
                         const std::string &what)
{
  const auto lo =
      input::parse_doubles(writer.get("Grid/Lower corner"), "Grid/Lower corner");
  const auto hi =
      input::parse_doubles(writer.get("Grid/Upper corner"), "Grid/Upper corner");
  if (lo.size() < 2 || hi.size() < 2)
    return; // the grid's own parsing names these entries
  const double box_lo[2] = {x0, y0}, box_hi[2] = {x1, y1};
  for (unsigned int d = 0; d < 2; ++d)
  {
    const double tol = 1e-9 * std::max(1.0, std::abs(hi[d] - lo[d]));
    if (box_lo[d] >= lo[d] - tol && box_hi[d] <= hi[d] + tol)
      continue;
    std::ostringstream msg;
    msg << what << " spans " << box_lo[d] << " to " << box_hi[d] << " m along "
        << "xy"[d] << ", beyond the background grid's " << lo[d] << " to " << hi[d]
        << " m: enlarge 'Grid/Lower corner' and 'Grid/Upper corner' with it";
    throw ExcBadInput(owner, msg.str());
  }
}

void set_notch_crack(EntryWriter &writer, const std::string &body,
                     const std::string &polyline, const std::string &owner)
{
  writer.set("Cracks/Polylines", polyline, owner);
  writer.set("Cracks/Grow with erosion", "false", owner);
  writer.set("Cracks/Body", std::to_string(writer.body(body, owner) + 1), owner);
}

template <int dim>
std::string box_shape(const double x0, const double y0, const double x1, const double y1,
                      const double length)
{
  if (dim == 2)
    return "rectangle(" + number(x0) + ", " + number(y0) + ", " + number(x1) + ", " +
           number(y1) + ")";
  return "rectangle(" + number(x0) + ", " + number(y0) + ", 0, " + number(x1) + ", " +
         number(y1) + ", " + number(length) + ")";
}

template <int dim>
std::string cylinder_shape(const double cx, const double cy, const double r,
                           const double length)
{
  std::string s = "cylinder(" + number(cx) + ", " + number(cy) + ", " + number(r);
  if (dim == 3)
    s += ", 0, " + number(length);
  return s + ")";
}

template <int dim>
std::string ramped_velocity(const Tensor<1, dim> &v, const double ramp)
{
  const std::string factor = ramp > 0 ? "(if(t < " + number(ramp) +
                                            ", 0.5 * (1 - cos(pi * t / " + number(ramp) +
                                            ")), 1))"
                                      : "1";
  std::string s;
  for (unsigned int d = 0; d < dim; ++d)
    s += (d > 0 ? "; " : "") + number(v[d]) + " * " + factor;
  return s;
}

template <int dim>
std::string ramped_velocity(const double vx, const double vy, const double ramp)
{
  // 0 in z: the scenes that give two components move in the x-y plane.
  Tensor<1, dim> v;
  v[0] = vx, v[1] = vy;
  return ramped_velocity<dim>(v, ramp);
}

template <int dim>
std::string load_fell_below(const SceneState<dim> &state, const unsigned int body,
                            const double fraction)
{
  if (fraction <= 0 || state.contact_forces == nullptr)
    return {};
  const double peak = (*state.peak_contact_forces)[body];
  if (!(peak > 0 && (*state.contact_forces)[body].norm() < fraction * peak))
    return {};
  // A load that dips while the contact forms (before anything softens) is not the
  // specimen failing. Every rank sees the same forces, so all of them ask this.
  if (state.particles != nullptr)
  {
    const auto &damage = state.particles->damage;
    double softening =
        std::any_of(damage.begin(), damage.end(), [](const double d) { return d > 0; })
            ? 1.0
            : 0.0;
    if (state.ranks != nullptr)
      softening = state.ranks->max(softening);
    if (softening == 0)
      return {};
  }
  return "the load fell below " + number(fraction) + " of its peak";
}

template <int dim>
CrackClusters crack_clusters(const ParticleStore<dim> &p, const unsigned int body,
                             const double thickness, const double threshold,
                             const double link_factor)
{
  CrackClusters result;
  std::vector<std::size_t> cracked;
  std::vector<double> size;
  double area = 0, largest = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.body_id[i] == body && p.damage[i] >= threshold)
    {
      const double a = p.initial_volume[i] / (dim == 2 ? thickness : 1.0);
      cracked.push_back(i), area += a;
      // A particle's size in the x-y plane: its area's side (in 3D its volume's cube
      // root).
      size.push_back(dim == 2 ? std::sqrt(a) : std::cbrt(a));
      largest = std::max(largest, size.back());
    }
  if (cracked.empty())
    return result;
  result.spacing =
      dim == 2 ? std::sqrt(area / cracked.size()) : std::cbrt(area / cracked.size());
  // Clusters of particles within link_factor times the larger of their two sizes of
  // each other (graded grids mix sizes), by union-find over square bins of the
  // longest link.
  const std::size_t n = cracked.size();
  std::vector<std::size_t> root(n);
  std::iota(root.begin(), root.end(), 0);
  const auto find = [&](std::size_t a)
  {
    while (root[a] != a)
      a = root[a] = root[root[a]];
    return a;
  };
  const double link = link_factor * largest;
  std::map<std::pair<long, long>, std::vector<std::size_t>> bins;
  const auto key = [&](const std::size_t k)
  {
    const auto &x = p.reference_position[cracked[k]];
    return std::make_pair(long(std::floor(x[0] / link)), long(std::floor(x[1] / link)));
  };
  for (std::size_t k = 0; k < n; ++k)
    bins[key(k)].push_back(k);
  for (std::size_t k = 0; k < n; ++k)
  {
    const auto [bx, by] = key(k);
    for (long dx = -1; dx <= 1; ++dx)
      for (long dy = -1; dy <= 1; ++dy)
      {
        const auto it = bins.find({bx + dx, by + dy});
        if (it == bins.end())
          continue;
        for (const std::size_t m : it->second)
        {
          const auto d =
              p.reference_position[cracked[k]] - p.reference_position[cracked[m]];
          const double pair = link_factor * std::max(size[k], size[m]);
          if (d[0] * d[0] + d[1] * d[1] <= pair * pair)
            root[find(k)] = find(m);
        }
      }
  }
  std::map<std::size_t, std::vector<std::size_t>> clusters;
  for (std::size_t k = 0; k < n; ++k)
    clusters[find(k)].push_back(cracked[k]);
  for (auto &[r, members] : clusters)
    result.clusters.push_back(std::move(members));
  return result;
}

double CrackPath::length() const
{
  if (points.empty())
    return 0;
  double l = spacing;
  for (std::size_t k = 1; k < points.size(); ++k)
    l += points[k].distance(points[k - 1]);
  return l;
}

template <int dim>
CrackPath crack_path(const ParticleStore<dim> &p, const unsigned int body,
                     const double thickness, const double threshold,
                     const Point<2> *origin)
{
  CrackPath path;
  const CrackClusters cracks = crack_clusters(p, body, thickness, threshold);
  path.spacing               = cracks.spacing;
  // The largest cluster, or with an origin the one that comes nearest to it (the
  // crack from a notch starts within a particle or two of the notch's tip).
  const std::vector<std::size_t> *largest = nullptr;
  double nearest                          = std::numeric_limits<double>::max();
  for (const auto &members : cracks.clusters)
  {
    if (origin == nullptr)
    {
      if (!largest || members.size() > largest->size())
        largest = &members;
      continue;
    }
    double d = std::numeric_limits<double>::max();
    for (const std::size_t i : members)
      d = std::min(d, std::hypot(p.reference_position[i][0] - (*origin)[0],
                                 p.reference_position[i][1] - (*origin)[1]));
    if (d < nearest)
      nearest = d, largest = &members;
  }
  if (largest == nullptr)
    return path;
  // Its main axis: the principal direction of the positions' covariance.
  double mx = 0, my = 0;
  for (const std::size_t i : *largest)
    mx += p.reference_position[i][0], my += p.reference_position[i][1];
  mx /= largest->size(), my /= largest->size();
  double cxx = 0, cxy = 0, cyy = 0;
  for (const std::size_t i : *largest)
  {
    const double dx = p.reference_position[i][0] - mx,
                 dy = p.reference_position[i][1] - my;
    cxx += dx * dx, cxy += dx * dy, cyy += dy * dy;
  }
  const double phi = 0.5 * std::atan2(2 * cxy, cxx - cyy);
  const double ux = std::cos(phi), uy = std::sin(phi);
  // Slices one spacing wide along the axis: their centroids, in order, and the
  // extent of their particles across the axis.
  struct Slice
  {
    double x = 0, y = 0, n = 0, lo = 1e300, hi = -1e300;
  };
  std::map<long, Slice> slices;
  const double s = path.spacing;
  for (const std::size_t i : *largest)
  {
    const double x = p.reference_position[i][0], y = p.reference_position[i][1];
    Slice &c            = slices[long(std::floor(((x - mx) * ux + (y - my) * uy) / s))];
    const double across = -(x - mx) * uy + (y - my) * ux;
    c.x += x, c.y += y, c.n += 1;
    c.lo = std::min(c.lo, across), c.hi = std::max(c.hi, across);
  }
  for (const auto &[index, c] : slices)
  {
    path.points.emplace_back(c.x / c.n, c.y / c.n);
    path.widths.push_back(c.hi - c.lo + s);
  }
  return path;
}

template <int dim>
double crack_path_length(const ParticleStore<dim> &p, const unsigned int body,
                         const double thickness, const double threshold)
{
  return crack_path(p, body, thickness, threshold).length();
}

double distance_to_polyline(const Point<2> &x, const std::vector<Point<2>> &line)
{
  if (line.size() == 1)
    return x.distance(line[0]);
  double d = std::numeric_limits<double>::max();
  for (std::size_t k = 1; k < line.size(); ++k)
  {
    const Tensor<1, 2> a = line[k] - line[k - 1], r = x - line[k - 1];
    const double t =
        a.norm_square() > 0 ? std::clamp((r * a) / a.norm_square(), 0.0, 1.0) : 0.0;
    d = std::min(d, (r - t * a).norm());
  }
  return d;
}

template <int dim>
CrackBand crack_band(const ParticleStore<dim> &p, const unsigned int body,
                     const CrackPath &path, const std::vector<Point<2>> &line)
{
  CrackBand band;
  if (path.widths.empty() || line.empty() || !p.kept_state().fracture)
    return band;
  // The median width over the central 80 % of the path.
  const std::size_t n = path.widths.size();
  std::vector<double> central(path.widths.begin() + n / 10,
                              path.widths.begin() + (n - n / 10));
  std::sort(central.begin(), central.end());
  band.width =
      central.size() % 2
          ? central[central.size() / 2]
          : 0.5 * (central[central.size() / 2 - 1] + central[central.size() / 2]);
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.body_id[i] == body && p.dissipated[i] > 0)
    {
      band.dissipated += p.dissipated[i];
      const Point<2> x(p.reference_position[i][0], p.reference_position[i][1]);
      if (distance_to_polyline(x, line) <= band.width)
        band.on_crack += p.dissipated[i];
    }
  band.off_crack_share =
      band.dissipated > 0 ? (band.dissipated - band.on_crack) / band.dissipated : 0.0;
  return band;
}

void add_crack_band(const CrackBand &band, std::map<std::string, double> &results)
{
  results["crack_band_width"]            = band.width;
  results["dissipation_off_crack_share"] = band.off_crack_share;
}

template <int dim>
void add_crack_energy(const ParticleStore<dim> &particles, const unsigned int body,
                      const double thickness, const double G_F,
                      std::map<std::string, double> &results)
{
  const double area     = crack_path_length(particles, body, thickness) * thickness;
  results["crack_area"] = area;
  const auto dissipated = results.find("dissipated_energy");
  if (G_F > 0 && area > 0 && dissipated != results.end())
    results["fracture_energy_ratio"] = dissipated->second / (G_F * area);
}

template <int dim>
double crack_plane_deviation(const ParticleStore<dim> &p, const unsigned int body,
                             const double cell, const double threshold)
{
  // Centroid first, then the spread about it: one pass of raw moments would lose the
  // digits of a spread far smaller than the distance from the origin.
  const auto failed = [&](const std::size_t i)
  { return p.body_id[i] == body && p.damage[i] >= threshold; };
  Tensor<1, dim> centroid;
  std::size_t n = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (failed(i))
      centroid += p.reference_position[i], ++n;
  if (n < dim + 1)
    return 0;
  centroid /= double(n);
  SymmetricTensor<2, dim> spread;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (failed(i))
    {
      const Tensor<1, dim> r = p.reference_position[i] - centroid;
      for (unsigned int a = 0; a < dim; ++a)
        for (unsigned int b = a; b < dim; ++b)
          spread[a][b] += r[a] * r[b];
    }
  spread /= double(n);
  // The mean squared distance from the best plane is the least eigenvalue.
  const double least = eigenvalues(spread)[dim - 1];
  return std::sqrt(std::max(least, 0.0)) / cell;
}

template <int dim>
double crack_tip_distance(const ParticleStore<dim> &p, const unsigned int body,
                          const double thickness, const Point<2> &origin,
                          const Tensor<1, 2> &direction, const double threshold)
{
  const CrackClusters cracks = crack_clusters(p, body, thickness, threshold, 1.75);
  const double reach         = 1.5 * cracks.spacing;
  const auto from_origin     = [&](const std::size_t i)
  {
    return Tensor<1, 2>(
        {p.reference_position[i][0] - origin[0], p.reference_position[i][1] - origin[1]});
  };
  double distance = 0;
  for (const auto &members : cracks.clusters)
  {
    // Only a crack that starts at the origin counts, not one elsewhere in the body.
    if (std::none_of(members.begin(), members.end(),
                     [&](const std::size_t i) { return from_origin(i).norm() <= reach; }))
      continue;
    for (const std::size_t i : members)
      distance = std::max(distance, from_origin(i) * direction);
  }
  return distance;
}

double rayleigh_wave_speed(const double E, const double nu, const double rho,
                           const bool plane_stress)
{
  // Shear and longitudinal speeds of the medium (a plate's in plane stress).
  const double cs = std::sqrt(E / (2 * rho * (1 + nu)));
  const double cp = plane_stress
                        ? std::sqrt(E / (rho * (1 - nu * nu)))
                        : std::sqrt(E * (1 - nu) / (rho * (1 + nu) * (1 - 2 * nu)));
  const double k2 = cs * cs / (cp * cp);
  // The Rayleigh equation in x = c_R / c_s, negative at 0.5 and positive at 1 for any
  // nu in [0, 0.5]: bisection.
  const auto f = [k2](const double x)
  {
    const double x2 = x * x;
    return (2 - x2) * (2 - x2) - 4 * std::sqrt(1 - x2) * std::sqrt(1 - k2 * x2);
  };
  double lo = 0.5, hi = 1;
  for (int i = 0; i < 60; ++i)
  {
    const double mid       = 0.5 * (lo + hi);
    (f(mid) < 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi) * cs;
}

double fracture_energy_of(const EntryWriter &writer, const unsigned int body)
{
  const std::string material =
      writer.get(input::subsection_name("Body", body) + "/Material");
  const std::string fracture = "Material " + material + "/Fracture/";
  if (writer.get(fracture + "Model") == "none")
    return 0;
  return std::stod(writer.get(fracture + "Fracture energy"));
}

template <int dim>
double damaged_volume(const ParticleStore<dim> &p, const unsigned int body)
{
  double damaged = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.body_id[i] == body && p.damage[i] > 0)
      damaged += p.damage[i] * p.mass[i] / p.density[i];
  return damaged;
}

template <int dim>
unsigned int body_index(const SceneState<dim> &state, const std::string &name,
                        const std::string &entry)
{
  const auto &names = *state.body_names;
  for (unsigned int b = 0; b < names.size(); ++b)
    if (names[b] == name)
      return b;
  AssertThrow(false, ExcBadInput(entry, "no Body N/Name is '" + name + "'"));
  return 0;
}

template <int dim>
const NodeConstraint<dim> &constraint_named(const SceneState<dim> &state,
                                            const std::string &name,
                                            const std::string &entry)
{
  const NodeConstraints<dim> &sets = *state.constraints;
  for (unsigned int c = 0; c < sets.size(); ++c)
    if (sets[c].name() == name)
      return sets[c];
  AssertThrow(false, ExcBadInput(entry, "no Boundary conditions/Constraint N/Name is '" +
                                            name + "'"));
  return sets[0];
}

void add_opening_gauge(EntryWriter &writer, const std::string &name, const Point<2> &a,
                       const Point<2> &b, const double radius)
{
  writer.append_item("Output/Opening gauges",
                     name + ": " + number(a[0]) + ", " + number(a[1]) + ", " +
                         number(b[0]) + ", " + number(b[1]) + ", " + number(radius));
}

template <int dim>
double gauge_reading(const SceneState<dim> &state, const std::string &name)
{
  const unsigned int g = state.gauges->find(name);
  Assert(g < state.gauges->size(), ExcInternalError());
  return state.gauges->read(*state.particles, nullptr)[g];
}

template <int dim>
void require_gauge_particles(const SceneState<dim> &state, const std::string &name,
                             const std::string &owner, const std::string &what)
{
  const unsigned int g = state.gauges->find(name);
  Assert(g < state.gauges->size(), ExcInternalError());
  for (unsigned int end = 0; end < 2; ++end)
    AssertThrow(state.gauges->mass_near(g, end, *state.particles) > 0,
                ExcBadInput(owner, "no particle of " + what +
                                       " lies within the radius of "
                                       "the opening gauge '" +
                                       name + "' (" + state.gauges->describe(g) + ")"));
}

template std::string box_shape<2>(double, double, double, double, double);
template std::string box_shape<3>(double, double, double, double, double);
template std::string cylinder_shape<2>(double, double, double, double);
template std::string cylinder_shape<3>(double, double, double, double);
template std::string ramped_velocity<2>(double, double, double);
template std::string ramped_velocity<3>(double, double, double);
template std::string ramped_velocity<2>(const Tensor<1, 2> &, double);
template std::string ramped_velocity<3>(const Tensor<1, 3> &, double);
template std::string load_fell_below(const SceneState<2> &, unsigned int, double);
template std::string load_fell_below(const SceneState<3> &, unsigned int, double);
template CrackClusters crack_clusters(const ParticleStore<2> &, unsigned int, double,
                                      double, double);
template CrackClusters crack_clusters(const ParticleStore<3> &, unsigned int, double,
                                      double, double);
template double crack_tip_distance(const ParticleStore<2> &, unsigned int, double,
                                   const Point<2> &, const Tensor<1, 2> &, double);
template double crack_tip_distance(const ParticleStore<3> &, unsigned int, double,
                                   const Point<2> &, const Tensor<1, 2> &, double);
template double crack_path_length(const ParticleStore<2> &, unsigned int, double, double);
template CrackPath crack_path(const ParticleStore<2> &, unsigned int, double, double,
                              const Point<2> *);
template CrackPath crack_path(const ParticleStore<3> &, unsigned int, double, double,
                              const Point<2> *);
template CrackBand crack_band(const ParticleStore<2> &, unsigned int, const CrackPath &,
                              const std::vector<Point<2>> &);
template CrackBand crack_band(const ParticleStore<3> &, unsigned int, const CrackPath &,
                              const std::vector<Point<2>> &);
template double crack_path_length(const ParticleStore<3> &, unsigned int, double, double);
template void add_crack_energy(const ParticleStore<2> &, unsigned int, double, double,
                               std::map<std::string, double> &);
template void add_crack_energy(const ParticleStore<3> &, unsigned int, double, double,
                               std::map<std::string, double> &);
template double crack_plane_deviation(const ParticleStore<2> &, unsigned int, double,
                                      double);
template double crack_plane_deviation(const ParticleStore<3> &, unsigned int, double,
                                      double);
template double damaged_volume(const ParticleStore<2> &, unsigned int);
template double damaged_volume(const ParticleStore<3> &, unsigned int);
template unsigned int body_index(const SceneState<2> &, const std::string &,
                                 const std::string &);
template unsigned int body_index(const SceneState<3> &, const std::string &,
                                 const std::string &);
template const NodeConstraint<2> &
constraint_named(const SceneState<2> &, const std::string &, const std::string &);
template const NodeConstraint<3> &
constraint_named(const SceneState<3> &, const std::string &, const std::string &);
template double gauge_reading(const SceneState<2> &, const std::string &);
template double gauge_reading(const SceneState<3> &, const std::string &);
template void require_gauge_particles(const SceneState<2> &, const std::string &,
                                      const std::string &, const std::string &);
template void require_gauge_particles(const SceneState<3> &, const std::string &,
                                      const std::string &, const std::string &);
} // namespace scenes
} // namespace lme_mpm
