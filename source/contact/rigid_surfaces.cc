#include <lme_mpm/base/format.h>
#include <lme_mpm/base/input.h>
#include <lme_mpm/base/parameters.h>
#include <lme_mpm/contact/rigid_surfaces.h>

#include <algorithm>
#include <cmath>

namespace lme_mpm
{
namespace
{
struct SurfaceEntries
{
  double penalty = 0.5, damping = 0.5;
  bool seat = false;
  void entries(EntryList &list)
  {
    list.add("Seat rigid surfaces", seat, "false", Patterns::Bool(),
             "Before the first step, carry each moving rigid exact surface along its "
             "prescribed velocity's direction (at the End time) until it touches the "
             "nearest particle domain in its path within a cell, as a testing machine "
             "is seated on the specimen: a curved body's particles lie up to a "
             "particle spacing inside its shape. The shift is seating_<body> in "
             "summary.json. Off: the surfaces start where their Shape puts them.");
    list.add("Surface damping ratio", damping, "0.5", Patterns::Double(),
             "zeta in [0, 1]: a dashpot beside the rigid surfaces' penalty spring, "
             "c = 2 zeta sqrt(k m_p) on the particle's normal speed relative to the "
             "surface. It damps the contact's own vibration, which an undamped spring "
             "lets grow under a deep, steady push (doc/contact.md); on a slowly "
             "loaded contact its force is a small share of the spring's.");
    list.add("Surface penalty factor", penalty, "0.5", Patterns::Double(),
             "alpha in (0, 1]: a rigid exact surface (Body N/Surface = exact) pushes a "
             "particle whose domain overlaps it by p with alpha m_p p / dt^2 (dt the "
             "wave speed's time step, from Time/CFL), which would remove alpha times "
             "the overlap in one step from a free particle. Above 1 the push "
             "overshoots; small values let particles sink in.");
  }
};
} // namespace

template <int dim>
void RigidSurfaces<dim>::declare_parameters(ParameterHandler &prm)
{
  prm.enter_subsection("Contact");
  EntryList::declare<SurfaceEntries>(prm);
  prm.leave_subsection();
}

template <int dim>
void RigidSurfaces<dim>::parse_parameters(ParameterHandler &prm,
                                          const Bodies<dim> &bodies_,
                                          const std::vector<double> &depth,
                                          const double h_min)
{
  margin = 2 * h_min;
  bodies = &bodies_;
  radius = depth;
  prm.enter_subsection("Contact");
  const SurfaceEntries in = EntryList::parse<SurfaceEntries>(prm);
  penalty                 = in.penalty;
  seat_surfaces           = in.seat;
  damping_ratio           = in.damping;
  friction                = prm.get_double("Friction coefficient");
  prm.leave_subsection();
  AssertThrow(penalty > 0 && penalty <= 1,
              ExcBadInput("Contact/Surface penalty factor",
                          "must lie in (0, 1], not " + format_double(penalty)));
  input::require_range(damping_ratio, 0, 1, false, "Contact/Surface damping ratio");
  surfaces.clear();
  const unsigned int n = bodies->size();
  for (unsigned int b = 0; b < n; ++b)
  {
    if (!bodies->exact(b))
      continue;
    const std::string section = input::subsection_name("Body", b);
    prm.enter_subsection(section);
    const std::string text = prm.get("Shape"), holes = prm.get("Holes");
    prm.leave_subsection();
    const auto &shapes = GeometryRegistry<dim>::instance();
    Surface s;
    s.body      = b;
    s.shape     = shapes.create(text, section + "/Shape");
    s.box       = s.shape->bounding_box();
    s.reference = s.box.center();
    for (const auto &h : input::split(holes, ';'))
      s.holes.push_back(shapes.create(h, section + "/Holes"));
    double phi;
    Tensor<1, dim> normal;
    AssertThrow(s.shape->signed_distance(s.reference, phi, normal),
                ExcBadInput(section + "/Shape",
                            "'" + text +
                                "' has no exact surface for Surface = exact: use a "
                                "rectangle, disc or cylinder"));
    for (const auto &h : s.holes)
      AssertThrow(h->signed_distance(s.reference, phi, normal),
                  ExcBadInput(section + "/Holes",
                              "a hole of a body with Surface = exact must be a "
                              "rectangle, disc or cylinder"));
    surfaces.push_back(std::move(s));
  }
  displacement.assign(n, Tensor<1, dim>());
  next_displacement = displacement;
  seating           = displacement;
  force             = displacement;
  velocity.assign(surfaces.size(), Tensor<1, dim>());
  shift = velocity;
  reach.assign(surfaces.size(), BoundingBox<dim>());
  max_overlap = 0;
}

template <int dim>
double RigidSurfaces<dim>::apply(GridTransfer<dim> &transfer,
                                 const ParticleStore<dim> &particles, const double t,
                                 const double dt)
{
  if (!active())
    return 0;
  std::fill(force.begin(), force.end(), Tensor<1, dim>());
  for (std::size_t i = 0; i < surfaces.size(); ++i)
  {
    const Surface &s = surfaces[i];
    // Where the surface stands: its travel and its seating.
    const Tensor<1, dim> u0    = displacement[s.body] + seating[s.body];
    const Tensor<1, dim> v_mid = bodies->velocity(s.body, s.reference + u0, t + 0.5 * dt);
    next_displacement[s.body]  = displacement[s.body] + dt * v_mid;
    shift[i]                   = u0 + dt * v_mid;
    velocity[i]                = bodies->velocity(s.body, s.reference + shift[i], t + dt);
    auto corners               = s.box.get_boundary_points();
    for (unsigned int d = 0; d < dim; ++d)
    {
      corners.first[d] += shift[i][d] - margin;
      corners.second[d] += shift[i][d] + margin;
    }
    reach[i] = BoundingBox<dim>(corners);
  }
  const Connectivity<dim> &conn            = transfer.connectivity();
  std::vector<Tensor<1, dim>> &nodal_force = transfer.nodes().force;
  Assert(reference_step > 0, ExcInternalError());
  const double stiffness = penalty / (reference_step * reference_step);
  // c / m = 2 zeta sqrt(k / m)
  const double damping = 2 * damping_ratio * std::sqrt(stiffness);
  double work = 0, overlap = max_overlap;
  for (std::size_t p = 0; p < particles.size(); ++p)
  {
    const unsigned int body = particles.body_id[p];
    if (bodies->prescribed(body))
      continue;
    const Point<dim> &x = particles.position[p];
    for (std::size_t i = 0; i < surfaces.size(); ++i)
    {
      if (!reach[i].point_inside(x))
        continue;
      const Surface &s          = surfaces[i];
      const Tensor<1, dim> rate = transfer.rate_at(p);
      const Point<dim> y        = x + dt * rate - shift[i];
      double phi;
      Tensor<1, dim> n;
      s.distance(y, phi, n);
      const double r_p   = radius[body];
      const double depth = r_p - phi;
      if (depth <= 0)
        continue;
      const double m                = particles.mass[p];
      const Tensor<1, dim> relative = rate - velocity[i];
      const double v_n              = relative * n;
      // The dashpot takes its share off the approach and separation speeds; a
      // surface only ever pushes.
      const double f_n = std::max(0.0, m * (stiffness * depth - damping * v_n));
      Tensor<1, dim> f = f_n * n;
      if (friction > 0)
      {
        const Tensor<1, dim> slip = relative - v_n * n;
        const double speed        = slip.norm();
        if (speed > 0)
          f -= (std::min(m * speed / dt, friction * f_n) / speed) * slip;
      }
      const std::size_t o = p * conn.stride;
      for (unsigned int k = 0; k < conn.n_nodes[p]; ++k)
        nodal_force[conn.nodes[o + k]] += conn.N[o + k] * f;
      // A ghost's push counts on its owner's rank.
      if (particles.ghost[p])
        continue;
      force[s.body] -= f;
      work += dt * (f * rate);
      overlap = std::max(overlap, depth / (2 * r_p));
    }
  }
  sums.assign(force.size() * dim + 1, 0.0);
  for (std::size_t b = 0; b < force.size(); ++b)
    for (unsigned int d = 0; d < dim; ++d)
      sums[b * dim + d] = force[b][d];
  sums.back() = work;
  if (ranks)
  {
    ranks->sum(sums);
    for (std::size_t b = 0; b < force.size(); ++b)
      for (unsigned int d = 0; d < dim; ++d)
        force[b][d] = sums[b * dim + d];
    max_overlap = ranks->max(overlap);
  }
  else
    max_overlap = overlap;
  return sums.back();
}

template <int dim>
void RigidSurfaces<dim>::seat(const ParticleStore<dim> &particles, const double end_time,
                              const double h_min)
{
  for (const Surface &s : surfaces)
  {
    // The overlaps at the start: their depth over the particle's radius, and the
    // surface's mean normal there.
    std::vector<double> sums(dim + 1, 0.0);
    double phi;
    Tensor<1, dim> n;
    for (std::size_t p = 0; p < particles.size(); ++p)
    {
      if (bodies->prescribed(particles.body_id[p]) || particles.ghost[p])
        continue;
      const double r_p = radius[particles.body_id[p]];
      s.distance(particles.position[p] - seating[s.body], phi, n);
      if (phi >= r_p)
        continue;
      sums[dim] = std::max(sums[dim], (r_p - phi) / r_p);
      for (unsigned int d = 0; d < dim; ++d)
        sums[d] += n[d];
    }
    const double deepest = ranks ? ranks->max(sums[dim]) : sums[dim];
    sums[dim]            = 0;
    if (ranks)
      ranks->sum(sums);
    const std::string section = input::subsection_name("Body", s.body);
    AssertThrow(seat_surfaces || deepest <= 0.1,
                ExcBadInput(section + "/Shape",
                            "the rigid surface overlaps particles of the other bodies "
                            "at the start by up to " +
                                format_double(deepest) +
                                " of their radius (more than 0.1): a curved body's "
                                "particles lie near its shape; move the shape, or set "
                                "Contact/Seat rigid surfaces = true"));
    if (!seat_surfaces)
      continue;
    // The direction the surface advances in: its velocity's, or for a surface at
    // rest, towards the particles it overlaps.
    Tensor<1, dim> d = bodies->velocity(s.body, s.reference, end_time);
    if (!(d.norm() > 0))
      for (unsigned int k = 0; k < dim; ++k)
        d[k] = sums[k];
    if (!(d.norm() > 0))
      continue;
    d /= d.norm();
    // Back off: each overlapping particle's travel with d (relative to the surface)
    // until its domain clears, at most a cell.
    double back = 0;
    for (std::size_t p = 0; p < particles.size(); ++p)
    {
      if (bodies->prescribed(particles.body_id[p]))
        continue;
      const double r_p   = radius[particles.body_id[p]];
      const Point<dim> x = particles.position[p] - seating[s.body];
      double t           = 0;
      for (unsigned int k = 0; k < 256 && t < h_min; ++k)
      {
        s.distance(x + t * d, phi, n);
        if (phi - r_p >= 0)
          break;
        t += std::max(r_p - phi, 1e-3 * h_min);
      }
      back = std::max(back, std::min(t, h_min));
    }
    if (ranks)
      back = ranks->max(back);
    seating[s.body] -= back * d;
    // Forward: sphere tracing on the signed distance, each particle's travel against
    // d until its domain touches the surface, given up beyond a cell.
    double travel = h_min;
    for (std::size_t p = 0; p < particles.size(); ++p)
    {
      if (bodies->prescribed(particles.body_id[p]))
        continue;
      const Point<dim> x = particles.position[p] - seating[s.body];
      double t           = 0;
      for (unsigned int k = 0; k < 64 && t < travel; ++k)
      {
        s.distance(x - t * d, phi, n);
        const double gap = phi - radius[particles.body_id[p]];
        if (gap < 1e-9 * h_min)
        {
          travel = std::min(travel, t);
          break;
        }
        t += gap;
      }
    }
    if (ranks)
      travel = -ranks->max(-travel);
    if (travel < h_min)
      seating[s.body] += travel * d;
  }
}

template <int dim>
void RigidSurfaces<dim>::add_results(std::map<std::string, double> &results) const
{
  if (!active())
    return;
  results["rigid_surface_max_overlap"] = max_overlap;
  for (const Surface &s : surfaces)
    if (!bodies->name(s.body).empty())
      results["seating_" + bodies->name(s.body)] = seating[s.body].norm();
}

template class RigidSurfaces<2>;
template class RigidSurfaces<3>;
} // namespace lme_mpm
