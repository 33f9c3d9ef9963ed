#include <lme_mpm/base/parallel.h>
#include <lme_mpm/fracture/neighbourhood.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>

namespace lme_mpm
{
template <int dim>
void Neighbourhood<dim>::keep_lists(const double new_skin)
{
  AssertThrow(new_skin >= 0 && std::isfinite(new_skin),
              ExcMessage("Neighbourhood::keep_lists: the skin must be >= 0"));
  if (new_skin != skin)
    lists_valid = false;
  skin = new_skin;
}

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
  search_radius = radius;
  rows          = 0;
  pairs         = 0;
  // Lists kept from an earlier build follow the particles through a sort. A store
  // changed otherwise since the last build (particles exchanged between ranks, which
  // on several ranks is every step, or added or removed) gets rows without a skin:
  // lists made now would not outlive the next exchange.
  const std::uint64_t now = store.order_version();
  const bool exchanged =
      now != seen_version && !(store.sorted_version() == now && seen_version + 1 == now);
  seen_version    = now;
  const bool keep = skin > 0 && !exchanged;
  if (keep)
    follow_order(store);
  else
    lists_valid = false;
  list.resize(keep && lists_valid ? kept_size : 0);
  begins.assign(n, 0);
  ends.assign(n, 0);
  wanted.assign(n, 0);
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
  several_bodies                         = false;
  for (std::size_t p = 0; p < n && !several_bodies; ++p)
    several_bodies = body[p] != body[0];

  const CellSearch<dim> cells(grid);
  wanted.assign(n, 1);
  if (seeds)
    mark_rows_near_seeds(store, cells, radius, *seeds, wanted);

  if (keep)
  {
    if (!lists_hold(store, radius))
    {
      // Lists for the particles within a second radius of a seed as well: the wanted
      // rows spread from the seeds as the stresses rise, and those within reach
      // then find their lists made.
      listed.assign(n, 1);
      if (seeds)
        mark_rows_near_seeds(store, cells, 2 * radius, *seeds, listed);
      fill_rows_of(store, cells, radius, skin, seeds != nullptr, listed, list_begins,
                   list_ends, {});
      kept_size      = list.size();
      built_position = store.position;
      built_radius   = radius;
      built_version  = store.order_version();
      listed_body.assign(*std::max_element(body.begin(), body.end()) + 1, 0);
      for (std::size_t p = 0; p < n; ++p)
        if (listed[p])
          listed_body[body[p]] = 1;
      lists_valid = true;
      ++list_builds;
    }
    rows_from_lists(store, radius, separated, may_be_separated);
  }
  else
  {
    // The rows whose pairs the crack test must see: one question per row, where most
    // rows lie far from every crack.
    mark_cut_rows(separated, may_be_separated);
    fill_rows_of(store, cells, radius, 0, seeds != nullptr, wanted, begins, ends,
                 separated);
    ++list_builds;
  }
  // Integer counts: the sum's order does not matter.
  struct Counts
  {
    std::size_t rows = 0, pairs = 0;
    Counts &operator+=(const Counts &o)
    {
      rows += o.rows, pairs += o.pairs;
      return *this;
    }
  };
  const Counts counts =
      parallel::deterministic_sum<Counts>(n,
                                          [&](const std::size_t b, const std::size_t e)
                                          {
                                            Counts c;
                                            for (std::size_t p = b; p < e; ++p)
                                              c.rows += wanted[p],
                                                  c.pairs += ends[p] - begins[p];
                                            return c;
                                          });
  rows  = counts.rows;
  pairs = counts.pairs;
}

template <int dim>
void Neighbourhood<dim>::mark_cut_rows(
    const std::function<bool(std::size_t, std::size_t)> &separated,
    const std::function<bool(std::size_t)> &may_be_separated)
{
  const std::size_t n = wanted.size();
  if (separated && !may_be_separated)
    cut = wanted;
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
  else
    cut.assign(n, 0);
}

template <int dim>
void Neighbourhood<dim>::rows_from_lists(
    const ParticleStore<dim> &store, const double radius,
    const std::function<bool(std::size_t, std::size_t)> &separated,
    const std::function<bool(std::size_t)> &may_be_separated)
{
  const std::size_t n = store.size();
  mark_cut_rows(separated, may_be_separated);
  // A row a crack may cut gets room behind the lists for its copy.
  std::size_t room = kept_size;
  for (std::size_t p = 0; p < n; ++p)
  {
    begins[p] = cut[p] ? room : list_begins[p];
    ends[p]   = wanted[p] && !cut[p] ? list_ends[p] : begins[p];
    room += cut[p] ? list_ends[p] - list_begins[p] : 0;
  }
  if (room == kept_size)
    return;
  list.resize(room);
  // The pairs within the radius that the crack leaves, as a build without a skin
  // finds them (same tests, same order).
  const std::vector<Point<dim>> &x = store.position;
  parallel::for_range(n,
                      [&](const std::size_t b, const std::size_t e)
                      {
                        for (std::size_t p = b; p < e; ++p)
                        {
                          if (!cut[p])
                            continue;
                          const double r = row_radius(p, radius), r2 = r * r;
                          std::size_t k = begins[p];
                          for (std::size_t i = list_begins[p]; i < list_ends[p]; ++i)
                          {
                            const std::uint32_t q = list[i];
                            if (x[q].distance_square(x[p]) <= r2 &&
                                (p == q || !separated(p, q)))
                              list[k++] = q;
                          }
                          ends[p] = k;
                        }
                      });
}

template <int dim>
void Neighbourhood<dim>::follow_order(const ParticleStore<dim> &store)
{
  const std::size_t n     = store.size();
  const std::uint64_t now = store.order_version();
  if (!lists_valid || now == built_version)
    return;
  // One sort since the lists were made (a build every step sees each): its permutation
  // carries them over. Anything else (an exchange between ranks, particles added or
  // removed) makes them anew.
  const std::vector<std::uint32_t> &from = store.sort_permutation();
  if (store.sorted_version() != now || built_version + 1 != now ||
      built_position.size() != n || from.size() != n)
  {
    lists_valid = false;
    return;
  }
  // One parallel pass: the inverse, and each particle's row and build position moved
  // with it (into buffers kept between builds).
  inverse.resize(n);
  moved_begins.resize(n);
  moved_ends.resize(n);
  moved_listed.resize(n);
  moved_position.resize(n);
  parallel::for_range(n,
                      [&](const std::size_t b, const std::size_t e)
                      {
                        for (std::size_t q = b; q < e; ++q)
                        {
                          const std::uint32_t f = from[q];
                          inverse[f]            = static_cast<std::uint32_t>(q);
                          moved_begins[q]       = list_begins[f];
                          moved_ends[q]         = list_ends[f];
                          moved_listed[q]       = listed[f];
                          moved_position[q]     = built_position[f];
                        }
                      });
  list_begins.swap(moved_begins);
  list_ends.swap(moved_ends);
  listed.swap(moved_listed);
  built_position.swap(moved_position);
  // ... and the rows name the new places, in increasing order again. The sort keeps
  // the order of the particles within each cell, so a row is out of order only where
  // a particle changed its cell: insertion sort, about linear.
  parallel::for_range(n,
                      [&](const std::size_t b, const std::size_t e)
                      {
                        for (std::size_t p = b; p < e; ++p)
                        {
                          if (!listed[p])
                            continue;
                          std::uint32_t *row = list.data() + list_begins[p],
                                        *end = list.data() + list_ends[p];
                          for (std::uint32_t *k = row; k != end; ++k)
                            *k = inverse[*k];
                          for (std::uint32_t *k = row + 1; k < end; ++k)
                          {
                            const std::uint32_t v = *k;
                            std::uint32_t *j      = k;
                            for (; j != row && *(j - 1) > v; --j)
                              *j = *(j - 1);
                            *j = v;
                          }
                        }
                      });
  built_version = now;
}

template <int dim>
bool Neighbourhood<dim>::lists_hold(const ParticleStore<dim> &store,
                                    const double radius) const
{
  const std::size_t n = store.size();
  if (!lists_valid || built_radius != radius || built_position.size() != n ||
      built_version != store.order_version())
    return false;
  // A pair left out was farther apart than radius + skin: it comes within the radius
  // only after one of the two has moved half the skin (less a margin for rounding).
  const double limit                     = 0.49 * skin * 0.49 * skin;
  const std::vector<Point<dim>> &x       = store.position;
  const std::vector<std::uint16_t> &body = store.body_id;
  std::atomic<bool> hold                 = true;
  parallel::for_range(n,
                      [&](const std::size_t b, const std::size_t e)
                      {
                        bool h = hold.load(std::memory_order_relaxed);
                        for (std::size_t p = b; p < e && h; ++p)
                          h = (!wanted[p] || listed[p]) &&
                              (body[p] >= listed_body.size() || !listed_body[body[p]] ||
                               x[p].distance_square(built_position[p]) <= limit);
                        if (!h)
                          hold.store(false, std::memory_order_relaxed);
                      });
  return hold.load();
}

template <int dim>
void Neighbourhood<dim>::fill_rows_of(
    const ParticleStore<dim> &store, const CellSearch<dim> &cells, const double radius,
    const double skin_added, const bool roomy, const std::vector<std::uint8_t> &which,
    std::vector<std::size_t> &row_begins, std::vector<std::size_t> &row_ends,
    const std::function<bool(std::size_t, std::size_t)> &separated)
{
  // `same` is a template argument so that a single body pays nothing for the body
  // test.
  const std::vector<std::uint16_t> &body = store.body_id;
  if (separated && several_bodies)
    fill_rows(
        store, cells, radius, skin_added,
        [&](const std::size_t p, const std::uint32_t q)
        { return body[p] == body[q] && (p == q || !cut[p] || !separated(p, q)); },
        roomy, which, row_begins, row_ends);
  else if (separated)
    fill_rows(
        store, cells, radius, skin_added,
        [&](const std::size_t p, const std::uint32_t q)
        { return p == q || !cut[p] || !separated(p, q); },
        roomy, which, row_begins, row_ends);
  else if (several_bodies)
    fill_rows(
        store, cells, radius, skin_added,
        [&](const std::size_t p, const std::uint32_t q) { return body[p] == body[q]; },
        roomy, which, row_begins, row_ends);
  else
    fill_rows(
        store, cells, radius, skin_added, [](std::size_t, std::uint32_t) { return true; },
        roomy, which, row_begins, row_ends);
}

template <int dim>
void Neighbourhood<dim>::mark_rows_near_seeds(const ParticleStore<dim> &store,
                                              const CellSearch<dim> &cells,
                                              const double radius,
                                              const std::vector<std::uint8_t> &seeds,
                                              std::vector<std::uint8_t> &marked)
{
  const std::size_t n                     = store.size();
  const std::vector<Point<dim>> &x        = store.position;
  const std::vector<std::size_t> &in_cell = store.cell_offsets();
  const std::size_t n_cells               = in_cell.size() - 1;
  const double r2                         = radius * radius;
  // The cells that hold a seed, and the cells within the radius of one: a particle
  // elsewhere has no seed near, which most particles learn from one look at their
  // cell's flag (a seeded cell's reach is searched from its own box, once). The seeds'
  // positions are gathered by cell (the store is sorted by cell), so that the search
  // reads the seeds alone.
  near_seeds.assign(n_cells, 0);
  seed_begin.assign(n_cells + 1, 0);
  seed_position.clear();
  for (std::size_t p = 0; p < n; ++p)
    if (seeds[p] & seed)
    {
      ++seed_begin[store.cell[p] + 1];
      seed_position.push_back(x[p]);
    }
  for (std::size_t c = 0; c < n_cells; ++c)
    seed_begin[c + 1] += seed_begin[c];
  typename CellSearch<dim>::Scratch scratch;
  for (std::size_t c = 0; c < n_cells; ++c)
    if (seed_begin[c + 1] > seed_begin[c])
    {
      const BoundingBox<dim> box = cells.box(c);
      cells.for_cells_near(box.center(),
                           radius + 0.5 * box.get_boundary_points().first.distance(
                                              box.get_boundary_points().second),
                           scratch, [&](const std::size_t k) { near_seeds[k] = 1; });
    }
  marked.resize(n);
  parallel::for_range(
      n,
      [&](const std::size_t b, const std::size_t e)
      {
        typename CellSearch<dim>::Scratch scratch;
        for (std::size_t p = b; p < e; ++p)
        {
          // A seed is within the radius of itself.
          bool near = (seeds[p] & takes_row) && (seeds[p] & seed);
          // The first seed within the radius answers.
          if ((seeds[p] & takes_row) && !near && near_seeds[store.cell[p]])
            near = cells.for_cells_near(
                x[p], radius, scratch,
                [&](const std::size_t c)
                {
                  for (std::size_t s = seed_begin[c]; s < seed_begin[c + 1]; ++s)
                    if (seed_position[s].distance_square(x[p]) <= r2)
                      return true;
                  return false;
                });
          marked[p] = near;
        }
      });
}

template <int dim>
template <class Same>
void Neighbourhood<dim>::fill_rows(const ParticleStore<dim> &store,
                                   const CellSearch<dim> &cells, const double radius,
                                   const double skin_added, const Same &same,
                                   const bool roomy,
                                   const std::vector<std::uint8_t> &which,
                                   std::vector<std::size_t> &row_begins,
                                   std::vector<std::size_t> &row_ends)
{
  const std::size_t n                     = store.size();
  const std::vector<Point<dim>> &x        = store.position;
  const std::vector<std::size_t> &in_cell = store.cell_offsets();
  // Each row to its particle's reach (cut_rows_to()) plus the skin.
  const auto reach = [&](const std::size_t p)
  { return row_radius(p, radius) + skin_added; };
  // Visits the neighbours of p in increasing cell index, and within a cell in
  // increasing particle index: increasing particle index over all, as the store is
  // sorted by cell. f(q) is called for each q within the reach that same accepts.
  const auto for_neighbours =
      [&](const std::size_t p, typename CellSearch<dim>::Scratch &scratch, auto &&f)
  {
    const double r = reach(p), r2 = r * r;
    cells.for_cells_near(x[p], r, scratch,
                         [&](const std::size_t c)
                         {
                           for (std::size_t s = in_cell[c]; s < in_cell[c + 1]; ++s)
                             if (x[s].distance_square(x[p]) <= r2 && same(p, s))
                               f(static_cast<std::uint32_t>(s));
                         });
  };
  // Row sizes first (row_begins[p + 1] holds p's), then their starts.
  row_begins.assign(n + 1, 0);
  parallel::for_range(n,
                      [&](const std::size_t b, const std::size_t e)
                      {
                        typename CellSearch<dim>::Scratch scratch;
                        for (std::size_t p = b; p < e; ++p)
                        {
                          std::size_t c = 0;
                          if (which[p] && roomy)
                            cells.for_cells_near(x[p], reach(p), scratch,
                                                 [&](const std::size_t k)
                                                 { c += in_cell[k + 1] - in_cell[k]; });
                          else if (which[p])
                            for_neighbours(p, scratch, [&](std::uint32_t) { ++c; });
                          row_begins[p + 1] = c;
                        }
                      });
  for (std::size_t p = 0; p < n; ++p)
    row_begins[p + 1] += row_begins[p];
  list.resize(row_begins[n]);
  row_begins.pop_back();
  row_ends.resize(n);
  parallel::for_range(n,
                      [&](const std::size_t b, const std::size_t e)
                      {
                        typename CellSearch<dim>::Scratch scratch;
                        for (std::size_t p = b; p < e; ++p)
                        {
                          std::size_t k = row_begins[p];
                          if (which[p])
                            for_neighbours(p, scratch,
                                           [&](const std::uint32_t q) { list[k++] = q; });
                          row_ends[p] = k;
                        }
                      });
}

template class Neighbourhood<2>;
template class Neighbourhood<3>;
} // namespace lme_mpm
