#include <lme_mpm/base/parallel.h>
#include <lme_mpm/fracture/neighbourhood.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace lme_mpm
{
template <int dim>
void Neighbourhood<dim>::build(
    const std::vector<Point<dim>> &x, const double radius,
    const std::vector<std::uint16_t> *body,
    const std::function<bool(std::size_t, std::size_t)> &separated,
    const std::vector<std::uint8_t> *seeds)
{
  const std::size_t n = x.size();
  Assert(!body || body->size() == n, ExcDimensionMismatch(body->size(), n));
  Assert(!seeds || seeds->size() == n, ExcDimensionMismatch(seeds->size(), n));
  offsets.assign(n + 1, 0);
  ends.assign(n, 0);
  list.clear();
  rows  = 0;
  pairs = 0;
  if (n == 0)
    return;
  // No seed (or no particle that takes a row), no row: nothing to bin.
  if (seeds)
  {
    std::uint8_t any = 0;
    for (const std::uint8_t f : *seeds)
      any |= f;
    if (any != (seed | takes_row))
      return;
  }

  // Cubes of side `radius` over the particles' bounding box; the same sweep finds
  // whether there is more than one body, as a single body needs no comparisons.
  Point<dim> lo = x[0], hi = x[0];
  bool several_bodies = false;
  for (std::size_t p = 0; p < n; ++p)
  {
    for (unsigned int d = 0; d < dim; ++d)
      lo[d] = std::min(lo[d], x[p][d]), hi[d] = std::max(hi[d], x[p][d]);
    several_bodies = several_bodies || (body && (*body)[p] != (*body)[0]);
  }
  std::array<std::uint32_t, dim> n_bins;
  std::size_t total = 1;
  for (unsigned int d = 0; d < dim; ++d)
  {
    n_bins[d] = static_cast<std::uint32_t>(
        std::min(1e6, std::floor((hi[d] - lo[d]) / radius)) + 1);
    total *= n_bins[d];
  }
  auto bin_index = [&](const Point<dim> &p, std::array<std::uint32_t, dim> &ijk)
  {
    std::size_t b = 0, stride = 1;
    for (unsigned int d = 0; d < dim; ++d)
    {
      ijk[d] = std::min<std::uint32_t>(n_bins[d] - 1, (p[d] - lo[d]) / radius);
      b += ijk[d] * stride;
      stride *= n_bins[d];
    }
    return b;
  };

  // Counting sort of particle indices by cube (stable: rows come out sorted).
  bin_of.resize(n);
  bin_start.assign(total + 1, 0);
  for (std::size_t p = 0; p < n; ++p)
  {
    std::array<std::uint32_t, dim> ijk;
    bin_of[p] = bin_index(x[p], ijk);
    ++bin_start[bin_of[p] + 1];
  }
  for (std::size_t b = 0; b < total; ++b)
    bin_start[b + 1] += bin_start[b];
  sorted.resize(n);
  {
    std::vector<std::uint32_t> next(bin_start.begin(), bin_start.end() - 1);
    for (std::size_t p = 0; p < n; ++p)
      sorted[next[bin_of[p]]++] = static_cast<std::uint32_t>(p);
  }

  const double r2 = radius * radius;
  // Calls g(b) for the (up to 3^dim) cubes around particle p, in increasing order.
  auto for_cubes = [&](const std::size_t p, auto &&g)
  {
    std::array<std::uint32_t, dim> c;
    bin_index(x[p], c);
    std::array<int, dim> k;
    k.fill(-1);
    while (true)
    {
      bool inside   = true;
      std::size_t b = 0, stride = 1;
      for (unsigned int d = 0; d < dim; ++d)
      {
        const long j = long(c[d]) + k[d];
        inside       = inside && j >= 0 && j < long(n_bins[d]);
        b += std::size_t(std::max(0L, j)) * stride;
        stride *= n_bins[d];
      }
      if (inside)
        g(b);
      unsigned int d = 0;
      while (d < dim && ++k[d] > 1)
        k[d++] = -1;
      if (d == dim)
        break;
    }
  };
  // Visits the neighbours of p in increasing index order of cubes; within a cube the
  // indices ascend. f(q) is called for each q within the radius that same(p, q)
  // accepts.
  auto for_neighbours = [&](const std::size_t p, auto &&same, auto &&f)
  {
    for_cubes(p,
              [&](const std::size_t b)
              {
                for (std::uint32_t s = bin_start[b]; s < bin_start[b + 1]; ++s)
                  if (x[sorted[s]].distance_square(x[p]) <= r2 && same(p, sorted[s]))
                    f(sorted[s]);
              });
  };

  // With seeds, only the particles that take a row and lie within the radius of a seed
  // get one. Cubes that hold no seed are skipped without looking at their particles.
  wanted.assign(n, 1);
  if (seeds)
  {
    seeded.assign(total, 0);
    for (std::size_t p = 0; p < n; ++p)
      seeded[bin_of[p]] |= (*seeds)[p] & seed;
    parallel::for_range(n,
                        [&](const std::size_t b, const std::size_t e)
                        {
                          for (std::size_t p = b; p < e; ++p)
                          {
                            bool near = false;
                            if ((*seeds)[p] & takes_row)
                              for_cubes(p,
                                        [&](const std::size_t c)
                                        {
                                          if (near || !seeded[c])
                                            return;
                                          for (std::uint32_t s = bin_start[c];
                                               s < bin_start[c + 1] && !near; ++s)
                                            near =
                                                ((*seeds)[sorted[s]] & seed) &&
                                                x[sorted[s]].distance_square(x[p]) <= r2;
                                        });
                            wanted[p] = near;
                          }
                        });
  }

  // Fills and sorts the rows; `same` is a template argument so that a single body pays
  // nothing for the body test. Every row gets room for all the particles of the cubes
  // around it, so one pass over the candidates fills it (the distance and crack tests
  // are the cost); without seeds, where every particle has a row and that room would be
  // about 3 (2D) or 6 (3D) times the rows, a counting pass sizes them exactly.
  auto fill = [&](auto &&same)
  {
    parallel::for_range(n,
                        [&](const std::size_t b, const std::size_t e)
                        {
                          for (std::size_t p = b; p < e; ++p)
                          {
                            std::size_t c = 0;
                            if (wanted[p] && seeds)
                              for_cubes(p, [&](const std::size_t k)
                                        { c += bin_start[k + 1] - bin_start[k]; });
                            else if (wanted[p])
                              for_neighbours(p, same, [&](std::uint32_t) { ++c; });
                            offsets[p + 1] = c;
                          }
                        });
    for (std::size_t p = 0; p < n; ++p)
    {
      rows += wanted[p];
      offsets[p + 1] += offsets[p];
    }
    list.resize(offsets[n]);
    ends.resize(n);
    parallel::for_range(n,
                        [&](const std::size_t b, const std::size_t e)
                        {
                          for (std::size_t p = b; p < e; ++p)
                          {
                            std::size_t k = offsets[p];
                            if (wanted[p])
                            {
                              for_neighbours(
                                  p, same, [&](const std::uint32_t q) { list[k++] = q; });
                              std::sort(list.begin() + offsets[p], list.begin() + k);
                            }
                            ends[p] = k;
                          }
                        });
    for (std::size_t p = 0; p < n; ++p)
      pairs += ends[p] - offsets[p];
  };
  if (separated && several_bodies)
    fill([&](const std::size_t p, const std::uint32_t q)
         { return (*body)[p] == (*body)[q] && (p == q || !separated(p, q)); });
  else if (separated)
    fill([&](const std::size_t p, const std::uint32_t q)
         { return p == q || !separated(p, q); });
  else if (several_bodies)
    fill([&](const std::size_t p, const std::uint32_t q)
         { return (*body)[p] == (*body)[q]; });
  else
    fill([](std::size_t, std::uint32_t) { return true; });
}

template class Neighbourhood<2>;
template class Neighbourhood<3>;
} // namespace lme_mpm
