#include <lme_mpm/contact/body_fields.h>

#include <algorithm>

namespace lme_mpm
{
template <int dim>
BodyFields<dim>::BodyFields(const BackgroundGrid<dim> &grid, const Bodies<dim> &bodies)
    : grid(grid), bodies(bodies)
{
}

template <int dim>
void BodyFields<dim>::set_up(const bool active, const double reach)
{
  is_active   = active;
  marks_valid = false;
  // The nodes a particle in cell i can reach along each direction: those within the
  // support radius of the cell (with a round-off margin).
  for (unsigned int d = 0; d < dim; ++d)
  {
    const auto &c          = grid.coordinates(d);
    const unsigned int n_c = c.size() - 1;
    const double margin    = 1e-9 * (c.back() - c.front());
    reach_lo[d].resize(n_c);
    reach_hi[d].resize(n_c);
    for (unsigned int i = 0; i < n_c; ++i)
    {
      const auto lo  = std::lower_bound(c.begin(), c.end(), c[i] - reach - margin);
      const auto hi  = std::upper_bound(c.begin(), c.end(), c[i + 1] + reach + margin);
      reach_lo[d][i] = static_cast<unsigned int>(lo - c.begin());
      reach_hi[d][i] = static_cast<unsigned int>(hi - c.begin()) - 1;
    }
  }
}

template <int dim>
void BodyFields<dim>::mark_reached_nodes(const ParticleStore<dim> &store)
{
  // The marks follow from the particles' cells and bodies alone: while neither has
  // changed (a slowly loaded specimen moves a particle to another cell once in many
  // steps) they stand, and the comparison costs a fraction of the marking.
  if (marks_valid && store.cell == marked_cells && store.body_id == marked_bodies)
    return;
  node_bodies.resize(grid.n_nodes(), 0);
  for (const unsigned int I : marked)
    node_bodies[I] = 0;
  marked.clear();
  const auto &offsets        = store.cell_offsets();
  const unsigned int n_cells = offsets.size() - 1;
  std::array<unsigned int, dim> n_in;
  for (unsigned int d = 0; d < dim; ++d)
    n_in[d] = grid.coordinates(d).size() - 1;
  for (unsigned int c = 0; c < n_cells; ++c)
  {
    if (offsets[c] == offsets[c + 1])
      continue;
    std::uint32_t here = 0;
    for (std::size_t p = offsets[c]; p < offsets[c + 1]; ++p)
      here |= std::uint32_t(1) << store.body_id[p];
    std::array<unsigned int, dim> ijk, lo, hi, node;
    unsigned int rest = c;
    for (unsigned int d = 0; d < dim; ++d)
    {
      ijk[d] = rest % n_in[d];
      rest /= n_in[d];
      lo[d] = reach_lo[d][ijk[d]];
      hi[d] = reach_hi[d][ijk[d]];
    }
    node = lo;
    while (true)
    {
      const unsigned int I = grid.node_index(node);
      if (node_bodies[I] == 0)
        marked.push_back(I);
      node_bodies[I] |= here;
      unsigned int d = 0;
      while (d < dim && ++node[d] > hi[d])
        node[d] = lo[d], ++d;
      if (d == dim)
        break;
    }
  }
  std::sort(marked.begin(), marked.end());
  marked_cells  = store.cell;
  marked_bodies = store.body_id;
  marks_valid   = true;
}

template <int dim>
void BodyFields<dim>::assign_fields(const ParticleStore<dim> &store,
                                    FieldLayout &field_layout)
{
  layout = &field_layout;
  touches.assign(store.size(), 0);
  if (!is_active)
    return;
  mark_reached_nodes(store);
  shared.clear();
  prescribed_fields.clear();
  for (const unsigned int I : marked)
  {
    const std::uint32_t m = node_bodies[I];
    if ((m & (m - 1)) != 0)
    {
      shared.push_back(I);
      for (std::uint32_t rest = m & (m - 1); rest != 0; rest &= rest - 1)
        field_layout.add(I, lowest_bit(rest));
    }
    if (bodies.any_prescribed())
      for (std::uint32_t rest = m; rest != 0; rest &= rest - 1)
      {
        const unsigned int b = lowest_bit(rest);
        if (bodies.prescribed(b))
          prescribed_fields.push_back(
              {b == lowest_bit(m) ? I : field_layout.find(I, b), b, I});
      }
  }
}

template <int dim>
void BodyFields<dim>::separate(Connectivity<dim> &conn, const ParticleStore<dim> &store,
                               const std::size_t begin, const std::size_t end)
{
  if (!is_active)
    return;
  const unsigned int n_grid = layout->n_grid_nodes();
  for (std::size_t p = begin; p < end; ++p)
  {
    const unsigned int body = store.body_id[p];
    const std::size_t o     = p * conn.stride;
    // Most particles are away from other bodies: one pass without branches finds that
    // each of their nodes holds their body alone (or is a crack's second field, which
    // stays with the cracked body), and the row stays as it is.
    const std::uint32_t own = std::uint32_t(1) << body;
    std::uint32_t in_all = own, others = 0;
    for (unsigned int k = 0; k < conn.n_nodes[p]; ++k)
    {
      const unsigned int I  = conn.nodes[o + k];
      const bool grid_node  = I < n_grid;
      const std::uint32_t m = grid_node ? node_bodies[grid_node ? I : 0] : own;
      in_all &= m;
      others |= m & ~own;
    }
    if (in_all == own && others == 0)
    {
      touches[p] = 0;
      continue;
    }
    std::uint8_t t = 0;
    for (unsigned int k = 0; k < conn.n_nodes[p]; ++k)
    {
      const unsigned int I = conn.nodes[o + k];
      if (I >= n_grid) // a crack's second field: stays with the cracked body
        continue;
      const std::uint32_t m = node_bodies[I];
      AssertThrow(
          m & (std::uint32_t(1) << body),
          ExcMessage("a support reaches past the shape function's support radius: "
                     "contact cannot give this particle its body's field"));
      if ((m & (m - 1)) == 0)
        continue;
      t = 1;
      if (lowest_bit(m) != body)
        conn.nodes[o + k] = layout->find(I, body);
    }
    touches[p] = t;
  }
}

template <int dim>
unsigned int BodyFields<dim>::field_of_body(const unsigned int I,
                                            const unsigned int body) const
{
  if (!is_active)
    return I;
  const std::uint32_t m = node_bodies[I];
  if ((m & (std::uint32_t(1) << body)) == 0)
    return FieldLayout::invalid;
  return lowest_bit(m) == body ? I : layout->find(I, body);
}

template <int dim>
void BodyFields<dim>::impose_prescribed_rates(std::vector<Tensor<1, dim>> &x,
                                              const std::vector<double> &mass,
                                              const double t) const
{
  for (const auto &pf : prescribed_fields)
    if (mass[pf.field] != 0)
      x[pf.field] = bodies.velocity(pf.body, grid.node_point(pf.node), t);
}

template <int dim>
void BodyFields<dim>::impose_prescribed_accelerations(std::vector<Tensor<1, dim>> &x,
                                                      const std::vector<double> &mass,
                                                      const double t,
                                                      const double h) const
{
  for (const auto &pf : prescribed_fields)
    if (mass[pf.field] != 0)
      x[pf.field] = bodies.acceleration(pf.body, grid.node_point(pf.node), t, h);
}

template class BodyFields<2>;
template class BodyFields<3>;
} // namespace lme_mpm
