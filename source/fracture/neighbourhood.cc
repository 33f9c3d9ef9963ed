#include <lme_mpm/base/parallel.h>
#include <lme_mpm/fracture/neighbourhood.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace lme_mpm
{
template <int dim>
void Neighbourhood<dim>::build(
    const ParticleStore<dim> &store, const BackgroundGrid<dim> &grid, const double radius,
    const std::function<bool(std::size_t, std::size_t)> &separated,
    const std::vector<std::uint8_t> *seeds,
    const std::function<bool(std::size_t)> &may_be_separated)
{
  const std::size_t n = store.size();
  Assert(!seeds || seeds->size() == n, ExcDimensionMismatch(seeds->size(), n));
  AssertThrow(store.cell_offsets().size() == grid.n_cells() + 1 &&
                  store.cell_offsets().back() == n,
              ExcMessage("Neighbourhood::build needs the particles sorted by the "
                         "grid's cells (ParticleStore::sort_by_cell)"));
  offsets.assign(n + 1, 0);
  ends.assign(n, 0);
  list.clear();
  rows  = 0;
  pairs = 0;
  if (n == 0)
    return;
  // No seed (or no particle that takes a row), no row: nothing to search.
  if (seeds)
  {
    std::uint8_t any = 0;
    for (const std::uint8_t f : *seeds)
      any |= f;
    if (any != (seed | takes_row))
      return;
  }
  // A single body needs no comparisons of bodies.
  const std::vector<std::uint16_t> &body = store.body_id;
  bool several_bodies                    = false;
  for (std::size_t p = 0; p < n && !several_bodies; ++p)
    several_bodies = body[p] != body[0];

  const CellSearch<dim> cells(grid);
  wanted.assign(n, 1);
  if (seeds)
    mark_rows_near_seeds(store, cells, radius, *seeds);

  // The rows whose pairs the crack test must see: one question per row, where most
  // rows lie far from every crack.
  if (separated && !may_be_separated)
    cut.assign(n, 1);
  else if (separated)
  {
    cut.resize(n);
    parallel::for_range(n,
                        [&](const std::size_t b, const std::size_t e)
                        {
                          for (std::size_t p = b; p < e; ++p)
                            cut[p] = wanted[p] && may_be_separated(p);
                        });
  }

  // `same` is a template argument so that a single body pays nothing for the body
  // test.
  const bool roomy = seeds != nullptr;
  if (separated && several_bodies)
    fill_rows(
        store, cells, radius,
        [&](const std::size_t p, const std::uint32_t q)
        { return body[p] == body[q] && (p == q || !cut[p] || !separated(p, q)); },
        roomy);
  else if (separated)
    fill_rows(
        store, cells, radius,
        [&](const std::size_t p, const std::uint32_t q)
        { return p == q || !cut[p] || !separated(p, q); },
        roomy);
  else if (several_bodies)
    fill_rows(
        store, cells, radius,
        [&](const std::size_t p, const std::uint32_t q) { return body[p] == body[q]; },
        roomy);
  else
    fill_rows(
        store, cells, radius, [](std::size_t, std::uint32_t) { return true; }, roomy);
}

template <int dim>
void Neighbourhood<dim>::mark_rows_near_seeds(const ParticleStore<dim> &store,
                                              const CellSearch<dim> &cells,
                                              const double radius,
                                              const std::vector<std::uint8_t> &seeds)
{
  const std::size_t n                     = store.size();
  const std::vector<Point<dim>> &x        = store.position;
  const std::vector<std::size_t> &in_cell = store.cell_offsets();
  const std::size_t n_cells               = in_cell.size() - 1;
  const double r2                         = radius * radius;
  // The cells that hold a seed, and the cells within the radius of one: a particle
  // elsewhere has no seed near, which most particles learn from one look at their
  // cell's flag (a seeded cell's reach is searched from its own box, once).
  seeded.assign(n_cells, 0);
  near_seeds.assign(n_cells, 0);
  for (std::size_t p = 0; p < n; ++p)
    seeded[store.cell[p]] |= seeds[p] & seed;
  typename CellSearch<dim>::Scratch scratch;
  for (std::size_t c = 0; c < n_cells; ++c)
    if (seeded[c])
    {
      const BoundingBox<dim> box = cells.box(c);
      cells.for_cells_near(box.center(),
                           radius + 0.5 * box.get_boundary_points().first.distance(
                                              box.get_boundary_points().second),
                           scratch, [&](const std::size_t k) { near_seeds[k] = 1; });
    }
  parallel::for_range(
      n,
      [&](const std::size_t b, const std::size_t e)
      {
        typename CellSearch<dim>::Scratch scratch;
        for (std::size_t p = b; p < e; ++p)
        {
          // A seed is within the radius of itself.
          bool near = (seeds[p] & takes_row) && (seeds[p] & seed);
          if ((seeds[p] & takes_row) && !near && near_seeds[store.cell[p]])
            cells.for_cells_near(
                x[p], radius, scratch,
                [&](const std::size_t c)
                {
                  if (near || !seeded[c])
                    return;
                  for (std::size_t s = in_cell[c]; s < in_cell[c + 1] && !near; ++s)
                    near = (seeds[s] & seed) && x[s].distance_square(x[p]) <= r2;
                });
          wanted[p] = near;
        }
      });
}

template <int dim>
template <class Same>
void Neighbourhood<dim>::fill_rows(const ParticleStore<dim> &store,
                                   const CellSearch<dim> &cells, const double radius,
                                   const Same &same, const bool roomy)
{
  const std::size_t n                     = store.size();
  const std::vector<Point<dim>> &x        = store.position;
  const std::vector<std::size_t> &in_cell = store.cell_offsets();
  const double r2                         = radius * radius;
  // Visits the neighbours of p in increasing cell index, and within a cell in
  // increasing particle index: increasing particle index over all, as the store is
  // sorted by cell. f(q) is called for each q within the radius that same accepts.
  const auto for_neighbours =
      [&](const std::size_t p, typename CellSearch<dim>::Scratch &scratch, auto &&f)
  {
    cells.for_cells_near(x[p], radius, scratch,
                         [&](const std::size_t c)
                         {
                           for (std::size_t s = in_cell[c]; s < in_cell[c + 1]; ++s)
                             if (x[s].distance_square(x[p]) <= r2 && same(p, s))
                               f(static_cast<std::uint32_t>(s));
                         });
  };
  parallel::for_range(n,
                      [&](const std::size_t b, const std::size_t e)
                      {
                        typename CellSearch<dim>::Scratch scratch;
                        for (std::size_t p = b; p < e; ++p)
                        {
                          std::size_t c = 0;
                          if (wanted[p] && roomy)
                            cells.for_cells_near(x[p], radius, scratch,
                                                 [&](const std::size_t k)
                                                 { c += in_cell[k + 1] - in_cell[k]; });
                          else if (wanted[p])
                            for_neighbours(p, scratch, [&](std::uint32_t) { ++c; });
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
                        typename CellSearch<dim>::Scratch scratch;
                        for (std::size_t p = b; p < e; ++p)
                        {
                          std::size_t k = offsets[p];
                          if (wanted[p])
                            for_neighbours(p, scratch,
                                           [&](const std::uint32_t q) { list[k++] = q; });
                          ends[p] = k;
                        }
                      });
  for (std::size_t p = 0; p < n; ++p)
    pairs += ends[p] - offsets[p];
}

template class Neighbourhood<2>;
template class Neighbourhood<3>;
} // namespace lme_mpm
