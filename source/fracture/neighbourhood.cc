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
  // A single body needs no comparisons of bodies.
  bool several_bodies = false;
  if (body)
    for (std::size_t p = 0; p < n && !several_bodies; ++p)
      several_bodies = (*body)[p] != (*body)[0];

  bins.build(x, radius);
  wanted.assign(n, 1);
  if (seeds)
    mark_rows_near_seeds(x, radius, *seeds);

  // `same` is a template argument so that a single body pays nothing for the body
  // test.
  const bool roomy = seeds != nullptr;
  if (separated && several_bodies)
    fill_rows(
        x, radius,
        [&](const std::size_t p, const std::uint32_t q)
        { return (*body)[p] == (*body)[q] && (p == q || !separated(p, q)); },
        roomy);
  else if (separated)
    fill_rows(
        x, radius,
        [&](const std::size_t p, const std::uint32_t q)
        { return p == q || !separated(p, q); },
        roomy);
  else if (several_bodies)
    fill_rows(
        x, radius,
        [&](const std::size_t p, const std::uint32_t q)
        { return (*body)[p] == (*body)[q]; },
        roomy);
  else
    fill_rows(
        x, radius, [](std::size_t, std::uint32_t) { return true; }, roomy);
}

template <int dim>
void Neighbourhood<dim>::mark_rows_near_seeds(const std::vector<Point<dim>> &x,
                                              const double radius,
                                              const std::vector<std::uint8_t> &seeds)
{
  const std::size_t n = x.size();
  const double r2     = radius * radius;
  seeded.assign(bins.n_bins(), 0);
  for (std::size_t p = 0; p < n; ++p)
    seeded[bins.bin_of(p)] |= seeds[p] & seed;
  parallel::for_range(n,
                      [&](const std::size_t b, const std::size_t e)
                      {
                        for (std::size_t p = b; p < e; ++p)
                        {
                          bool near = false;
                          if (seeds[p] & takes_row)
                            bins.for_cubes(x[p],
                                           [&](const std::size_t c)
                                           {
                                             if (near || !seeded[c])
                                               return;
                                             for (auto s = bins.begin(c);
                                                  s != bins.end(c) && !near; ++s)
                                               near = (seeds[*s] & seed) &&
                                                      x[*s].distance_square(x[p]) <= r2;
                                           });
                          wanted[p] = near;
                        }
                      });
}

template <int dim>
template <class Same>
void Neighbourhood<dim>::fill_rows(const std::vector<Point<dim>> &x, const double radius,
                                   const Same &same, const bool roomy)
{
  const std::size_t n = x.size();
  const double r2     = radius * radius;
  // Visits the neighbours of p in increasing index order of cubes; within a cube the
  // indices ascend. f(q) is called for each q within the radius that same accepts.
  const auto for_neighbours = [&](const std::size_t p, auto &&f)
  {
    bins.for_cubes(x[p],
                   [&](const std::size_t b)
                   {
                     for (auto s = bins.begin(b); s != bins.end(b); ++s)
                       if (x[*s].distance_square(x[p]) <= r2 && same(p, *s))
                         f(*s);
                   });
  };
  parallel::for_range(n,
                      [&](const std::size_t b, const std::size_t e)
                      {
                        for (std::size_t p = b; p < e; ++p)
                        {
                          std::size_t c = 0;
                          if (wanted[p] && roomy)
                            bins.for_cubes(x[p], [&](const std::size_t k)
                                           { c += bins.end(k) - bins.begin(k); });
                          else if (wanted[p])
                            for_neighbours(p, [&](std::uint32_t) { ++c; });
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
                            for_neighbours(p,
                                           [&](const std::uint32_t q) { list[k++] = q; });
                            std::sort(list.begin() + offsets[p], list.begin() + k);
                          }
                          ends[p] = k;
                        }
                      });
  for (std::size_t p = 0; p < n; ++p)
    pairs += ends[p] - offsets[p];
}

template class Neighbourhood<2>;
template class Neighbourhood<3>;
} // namespace lme_mpm
