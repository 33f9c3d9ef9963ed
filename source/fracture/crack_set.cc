#include <lme_mpm/base/input.h>
#include <lme_mpm/base/parameters.h>
#include <lme_mpm/fracture/crack_set.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace lme_mpm
{
namespace
{
// Twice the signed area of (a, b, c): > 0 if c lies left of a -> b.
template <int dim>
double orientation(const Point<dim> &a, const Point<dim> &b, const Point<dim> &c)
{
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

template <int dim>
double distance_to_segment(const Point<dim> &x, const Point<dim> &a, const Point<dim> &b)
{
  const Tensor<1, dim> ab = b - a;
  const double L2         = ab.norm_square();
  const double s          = L2 > 0 ? std::clamp(((x - a) * ab) / L2, 0.0, 1.0) : 0.0;
  return (x - (a + s * ab)).norm();
}
} // namespace

namespace
{
/// The "Cracks" entries, listed once for declaring and reading.
struct CrackEntries
{
  std::string polylines;
  bool grow = true, contact = true;
  unsigned int body = 1;

  void entries(EntryList &list)
  {
    list.enter("Cracks");
    list.add(
        "Polylines", polylines, "", Patterns::Anything(),
        "Explicit cracks (2D): each a polyline 'x0, y0, x1, y1, ...' (m), several "
        "separated by ';'. Grid nodes near a crack carry a second velocity field, so the "
        "crack faces move independently even where a node's support spans both (CRAMP). "
        "Put a crack on the centre line of a notch that its support would bridge, or "
        "through intact particles for a sharp crack; one that opens on a free edge "
        "should start a support radius outside it, so that no particle-node line "
        "passes round its mouth. Empty: none.");
    list.add("Body", body, "1", Patterns::Integer(1),
             "The body N ('Body N') the cracks cut. Only its particles are sent to the "
             "second fields, so that with multi-field contact another body near a crack "
             "keeps its own field and the faces' contact pairs the cracked body's "
             "fields.");
    list.add("Grow with erosion", grow, "true", Patterns::Bool(),
             "Extend each crack tip along the failed particles ahead of it, so "
             "that a crack grown by eigenerosion or eigensoftening separates the "
             "velocity field as the initial crack does.");
    list.add("Face contact", contact, "true", Patterns::Bool(),
             "Keep crack faces that move towards each other from passing "
             "through one another (frictionless contact between the two fields "
             "of a node).");
    list.leave();
  }
};
} // namespace

template <int dim>
void CrackSet<dim>::declare_parameters(ParameterHandler &prm)
{
  EntryList list(prm, EntryList::Mode::declare);
  CrackEntries().entries(list);
}

template <int dim>
void CrackSet<dim>::parse_parameters(ParameterHandler &prm, const unsigned int n_bodies)
{
  CrackEntries in;
  EntryList list(prm, EntryList::Mode::parse);
  in.entries(list);
  growing                 = in.grow;
  contact                 = in.contact;
  const std::string entry = "Cracks/Polylines";
  lines.clear();
  AssertThrow(in.body >= 1 && in.body <= n_bodies,
              ExcBadInput("Cracks/Body",
                          "must name one of the " + std::to_string(n_bodies) +
                              " bodies: an integer in [1, " + std::to_string(n_bodies) +
                              "], got " + std::to_string(in.body)));
  cracked_body = in.body - 1;
  for (const auto &text : input::split(in.polylines, ';'))
  {
    AssertThrow(dim == 2,
                ExcBadInput(entry, "explicit cracks are available in 2D only (got '" +
                                       text + "' in a " + std::to_string(dim) +
                                       "D run); leave the entry empty"));
    const std::vector<double> v = input::parse_doubles(text, entry);
    AssertThrow(v.size() >= 4 && v.size() % 2 == 0,
                ExcBadInput(entry, "'" + text +
                                       "' needs an even number of coordinates, at least "
                                       "two points (x0, y0, x1, y1, ...)"));
    std::vector<Point<dim>> line;
    for (std::size_t i = 0; i + 1 < v.size(); i += 2)
    {
      Point<dim> x;
      x[0] = v[i];
      x[1] = v[i + 1];
      AssertThrow(line.empty() || (x - line.back()).norm() > 0,
                  ExcBadInput(entry, "'" + text + "' repeats a point"));
      line.push_back(x);
    }
    lines.push_back(std::move(line));
  }
}

template <int dim>
void CrackSet<dim>::assign_fields(const BackgroundGrid<dim> &grid, const double reach,
                                  FieldLayout &layout)
{
  if (lines.empty())
    return;
  const unsigned int n_nodes = grid.n_nodes();
  second.resize(n_nodes, numbers::invalid_unsigned_int);
  // Candidate segments per grid node, then the rows in extra-node order.
  std::vector<std::vector<std::pair<unsigned int, unsigned int>>> near(
      extra_primary.size());
  for (unsigned int l = 0; l < lines.size(); ++l)
    for (unsigned int s = 0; s + 1 < lines[l].size(); ++s)
    {
      const Point<dim> &a = lines[l][s], &b = lines[l][s + 1];
      // Index range of the nodes in the segment's box widened by the reach.
      std::array<unsigned int, dim> lo, hi;
      for (unsigned int d = 0; d < dim; ++d)
      {
        const auto &c   = grid.coordinates(d);
        const double x0 = std::min(a[d], b[d]) - reach, x1 = std::max(a[d], b[d]) + reach;
        lo[d] = std::lower_bound(c.begin(), c.end(), x0) - c.begin();
        hi[d] = std::upper_bound(c.begin(), c.end(), x1) - c.begin();
      }
      if constexpr (dim == 2)
        for (unsigned int j = lo[1]; j < hi[1]; ++j)
          for (unsigned int i = lo[0]; i < hi[0]; ++i)
          {
            const unsigned int I = grid.node_index({{i, j}});
            const Point<dim> x   = grid.node_point(I);
            if (distance_to_segment(x, a, b) > reach)
              continue;
            if (second[I] == numbers::invalid_unsigned_int)
            {
              second[I] = extra_primary.size();
              extra_primary.push_back(I);
              extra_field.push_back(layout.add(I, FieldLayout::crack_side));
              extra_point.push_back(x);
              near.emplace_back();
            }
            near[second[I]].emplace_back(l, s);
          }
    }
  segment_offsets.assign(1, 0);
  segments.clear();
  for (const auto &row : near)
  {
    segments.insert(segments.end(), row.begin(), row.end());
    segment_offsets.push_back(segments.size());
  }
  update_normals();
}

template <int dim>
void CrackSet<dim>::update_normals()
{
  // From the nearest candidate segment, with the side test crosses() uses (a point on
  // the line counts as left of it), so that the normal always points from the node's
  // own field to the other.
  extra_normal.resize(extra_primary.size());
  for (unsigned int J = 0; J < extra_primary.size(); ++J)
  {
    const Point<dim> &x = extra_point[J];
    double nearest      = std::numeric_limits<double>::max();
    for (unsigned int k = segment_offsets[J]; k < segment_offsets[J + 1]; ++k)
    {
      const auto [l, s]   = segments[k];
      const Point<dim> &a = lines[l][s], &b = lines[l][s + 1];
      const double dist = distance_to_segment(x, a, b);
      if (dist >= nearest)
        continue;
      nearest                = dist;
      const Tensor<1, dim> t = (b - a) / (b - a).norm();
      Tensor<1, dim> left;
      left[0]         = -t[1];
      left[1]         = t[0];
      extra_normal[J] = orientation(a, b, x) >= 0 ? -left : left;
    }
  }
}

template <int dim>
bool CrackSet<dim>::crosses(const Point<dim> &p, const Point<dim> &q,
                            const unsigned int J) const
{
  // The particle-node line p -> q crosses a crack segment a -> b if p and q lie on
  // different sides of a -> b (a point on it counts as left, so a node on the crack
  // line belongs to one face) and a, b are not both strictly on one side of p -> q.
  for (unsigned int k = segment_offsets[J]; k < segment_offsets[J + 1]; ++k)
  {
    const auto [l, s]   = segments[k];
    const Point<dim> &a = lines[l][s], &b = lines[l][s + 1];
    if ((orientation(a, b, p) >= 0) == (orientation(a, b, q) >= 0))
      continue;
    const double oa = orientation(p, q, a), ob = orientation(p, q, b);
    if ((oa <= 0 && ob >= 0) || (oa >= 0 && ob <= 0))
      return true;
  }
  return false;
}

template <int dim>
void CrackSegmentBins<dim>::build(const std::vector<std::vector<Point<dim>>> &all,
                                  const double radius)
{
  lines = &all;
  bins.clear();
  side = radius;
  if (all.empty() || !(radius > 0))
    return;
  const auto &lines = all;
  Point<dim> lo = lines[0][0], hi = lo;
  for (const auto &line : lines)
    for (const auto &x : line)
      for (unsigned int d = 0; d < dim; ++d)
        lo[d] = std::min(lo[d], x[d]), hi[d] = std::max(hi[d], x[d]);
  lower            = lo;
  std::size_t size = 1;
  for (unsigned int d = 0; d < dim; ++d)
  {
    n_bins[d] = static_cast<unsigned int>(std::min(1e4, (hi[d] - lo[d]) / radius)) + 1;
    size *= n_bins[d];
  }
  bins.resize(size);
  // Every bin a segment's bounding box overlaps holds it.
  for (unsigned int l = 0; l < lines.size(); ++l)
    for (unsigned int s = 0; s + 1 < lines[l].size(); ++s)
    {
      std::array<unsigned int, dim> first, last;
      for (unsigned int d = 0; d < dim; ++d)
      {
        const double a = lines[l][s][d] - lo[d], b = lines[l][s + 1][d] - lo[d];
        first[d] = std::min(n_bins[d] - 1, unsigned(std::min(a, b) / radius));
        last[d]  = std::min(n_bins[d] - 1, unsigned(std::max(a, b) / radius));
      }
      std::array<unsigned int, dim> k = first;
      while (true)
      {
        std::size_t b = 0, stride = 1;
        for (unsigned int d = 0; d < dim; ++d)
          b += k[d] * stride, stride *= n_bins[d];
        bins[b].emplace_back(l, s);
        unsigned int d = 0;
        while (d < dim && ++k[d] > last[d])
          k[d] = first[d], ++d;
        if (d == dim)
          break;
      }
    }
}

template <int dim>
template <class F>
bool CrackSegmentBins<dim>::any_bin_over(const Point<dim> &lo, const Point<dim> &hi,
                                         const F &f) const
{
  std::array<unsigned int, dim> first, last;
  for (unsigned int d = 0; d < dim; ++d)
  {
    const double a = lo[d] - lower[d], b = hi[d] - lower[d];
    if (b < 0 || a > n_bins[d] * side)
      return false;
    first[d] = std::min(n_bins[d] - 1, unsigned(std::max(0.0, a) / side));
    last[d]  = std::min(n_bins[d] - 1, unsigned(b / side));
  }
  std::array<unsigned int, dim> k = first;
  while (true)
  {
    std::size_t b = 0, stride = 1;
    for (unsigned int d = 0; d < dim; ++d)
      b += k[d] * stride, stride *= n_bins[d];
    if (f(bins[b]))
      return true;
    unsigned int d = 0;
    while (d < dim && ++k[d] > last[d])
      k[d] = first[d], ++d;
    if (d == dim)
      return false;
  }
}

template <int dim>
bool CrackSegmentBins<dim>::separates(const Point<dim> &p, const Point<dim> &q) const
{
  if (bins.empty())
    return false;
  const auto &lines = *this->lines;
  // A segment that crosses p -> q holds a point of it, so it is in one of the (at
  // most 2^dim) bins the pair's bounding box overlaps.
  Point<dim> lo, hi;
  for (unsigned int d = 0; d < dim; ++d)
    lo[d] = std::min(p[d], q[d]), hi[d] = std::max(p[d], q[d]);
  return any_bin_over(
      lo, hi,
      [&](const std::vector<std::pair<unsigned int, unsigned int>> &bin)
      {
        for (const auto &[l, s] : bin)
        {
          // The crosses() test: p, q on different sides of a -> b (a point on the line
          // counts as left), and a, b not both strictly on one side of p -> q.
          const Point<dim> &a = lines[l][s], &e = lines[l][s + 1];
          if ((orientation(a, e, p) >= 0) == (orientation(a, e, q) >= 0))
            continue;
          const double oa = orientation(p, q, a), ob = orientation(p, q, e);
          if (!((oa <= 0 && ob >= 0) || (oa >= 0 && ob <= 0)))
            continue;
          // Crossed: still connected if the path round an end of the crack is within
          // the radius (near a tip the material joins the two faces).
          const Point<dim> &first = lines[l].front(), &last = lines[l].back();
          const double detour = std::min(p.distance(first) + first.distance(q),
                                         p.distance(last) + last.distance(q));
          if (detour > side)
            return true;
        }
        return false;
      });
}

template <int dim>
bool CrackSegmentBins<dim>::may_separate(const Point<dim> &p) const
{
  if (bins.empty())
    return false;
  // The bins of every pair's box lie among those of the box p +- radius (widened a
  // little, as a pair within the radius by its rounded distance may reach a hair
  // beyond it along one direction).
  Point<dim> lo, hi;
  for (unsigned int d = 0; d < dim; ++d)
    lo[d] = p[d] - side * (1 + 1e-9), hi[d] = p[d] + side * (1 + 1e-9);
  return any_bin_over(lo, hi,
                      [](const std::vector<std::pair<unsigned int, unsigned int>> &bin)
                      { return !bin.empty(); });
}

template <int dim>
void CrackSet<dim>::separate(const ParticleStore<dim> &particles,
                             const BackgroundGrid<dim> &grid, Connectivity<dim> &conn,
                             const std::size_t begin, const std::size_t end,
                             std::uint8_t *touched) const
{
  if (lines.empty())
    return;
  for (std::size_t p = begin; p < end; ++p)
  {
    touched[p] = 0;
    if (particles.body_id[p] != cracked_body)
      continue;
    unsigned int *nodes = &conn.nodes[p * conn.stride];
    bool near           = false;
    for (unsigned int k = 0; k < conn.n_nodes[p]; ++k)
    {
      const unsigned int J = second[nodes[k]];
      if (J == numbers::invalid_unsigned_int)
        continue;
      near = true;
      if (crosses(particles.position[p], grid.node_point(nodes[k]), J))
        nodes[k] = extra_field[J];
    }
    touched[p] = near;
  }
}

template <int dim>
bool CrackSet<dim>::grow(const ParticleStore<dim> &particles,
                         const double particle_spacing)
{
  if (lines.empty() || !growing)
    return false;
  std::vector<std::size_t> failed;
  for (std::size_t p = 0; p < particles.size(); ++p)
    if (particles.failed[p])
      failed.push_back(p);
  if (failed.empty())
    return false;
  const double max_step = growth_reach(particle_spacing),
               min_step = 0.5 * particle_spacing;
  bool grown            = false;
  for (auto &line : lines)
    for (const bool at_end : {true, false})
      for (;;)
      {
        // The tip's direction over the last 2 max_step of the crack: a wide band of
        // failed particles then cannot turn it around step by step.
        const std::size_t n = line.size();
        const auto point    = [&](const std::size_t i) -> const Point<dim> &
        { return at_end ? line[n - 1 - i] : line[i]; };
        const Point<dim> tip = point(0);
        std::size_t back     = 1;
        while (back + 1 < n && (tip - point(back)).norm() < 2 * max_step)
          ++back;
        const Tensor<1, dim> t = (tip - point(back)) / (tip - point(back)).norm();
        // The failed particle most straight ahead, within 45 degrees.
        double best_score = -1;
        std::size_t best  = particles.size();
        for (const std::size_t p : failed)
        {
          const Tensor<1, dim> d = particles.position[p] - tip;
          const double dist = d.norm(), ahead = d * t;
          const double lateral = std::sqrt(std::max(0.0, dist * dist - ahead * ahead));
          if (dist <= max_step && ahead >= min_step && ahead >= lateral &&
              ahead - lateral > best_score)
            best_score = ahead - lateral, best = p;
        }
        if (best == particles.size())
          break;
        // A failed particle with no intact one near it has drifted out of the body
        // (eroded particles keep their mass): the crack has run through.
        bool in_body = false;
        for (std::size_t p = 0; p < particles.size() && !in_body; ++p)
          in_body = !particles.failed[p] &&
                    (particles.position[p] - particles.position[best]).norm() <= max_step;
        if (!in_body)
          break;
        if (at_end)
          line.push_back(particles.position[best]);
        else
          line.insert(line.begin(), particles.position[best]);
        grown = true;
      }
  return grown;
}

template <int dim>
void CrackSet<dim>::restore(std::vector<std::vector<Point<dim>>> saved)
{
  Assert(saved.size() == lines.size(), ExcDimensionMismatch(saved.size(), lines.size()));
  for (const auto &line : saved)
    AssertThrow(line.size() >= 2,
                ExcBadInput("--resume", "the checkpoint's crack data are corrupt"));
  lines = std::move(saved);
  // The fields are reassigned from the restored lines; their numbering may differ
  // from the uninterrupted run's, which changes no sum (each field is summed in
  // particle order like any node).
  second.clear();
  extra_primary.clear();
  extra_field.clear();
  extra_point.clear();
  extra_normal.clear();
}

template class CrackSet<2>;
template class CrackSet<3>;
template class CrackSegmentBins<2>;
template class CrackSegmentBins<3>;
} // namespace lme_mpm
