#ifndef LME_MPM_GRID_FIELD_LAYOUT_H
#define LME_MPM_GRID_FIELD_LAYOUT_H

#include <deal.II/base/types.h>

#include <vector>

namespace lme_mpm
{
/**
 * Which velocity fields the grid nodes carry. Every grid node I has its own field,
 * with index I; a node where material must move independently on either side (the
 * two faces of a crack, or two bodies in contact) carries extra fields, numbered
 * past the grid's nodes, each with a tag saying whose it is. Nodal arrays are sized
 * n_fields(), so every nodal loop treats an extra field like any node, and a node
 * with no extra field costs what it did on a single-field grid.
 */
class FieldLayout
{
public:
  static constexpr unsigned int invalid = dealii::numbers::invalid_unsigned_int;
  /// The tag of the field on the far side of an explicit crack.
  static constexpr unsigned int crack_side = 0xfffffff0u;

  /// Drops all extra fields of a grid of @p n_grid_nodes nodes.
  void reinit(const unsigned int n_grid_nodes)
  {
    n_grid = n_grid_nodes;
    first_extra.assign(n_grid_nodes, invalid);
    owner.clear();
    next.clear();
    tags.clear();
  }

  unsigned int n_grid_nodes() const { return n_grid; }
  unsigned int n_extra() const { return owner.size(); }
  unsigned int n_fields() const { return n_grid + owner.size(); }

  /// The field of grid node @p I tagged @p tag, created if it does not exist yet.
  unsigned int add(const unsigned int I, const unsigned int tag)
  {
    const unsigned int found = find(I, tag);
    if (found != invalid)
      return found;
    const unsigned int F = n_grid + owner.size();
    // Appended at the end of the node's chain, so the chain stays in creation order.
    unsigned int *link = &first_extra[I];
    while (*link != invalid)
      link = &next[*link - n_grid];
    *link = F;
    owner.push_back(I);
    next.push_back(invalid);
    tags.push_back(tag);
    return F;
  }

  /// The field of grid node @p I tagged @p tag, or invalid.
  unsigned int find(const unsigned int I, const unsigned int tag) const
  {
    if (I >= first_extra.size())
      return invalid;
    for (unsigned int F = first_extra[I]; F != invalid; F = next[F - n_grid])
      if (tags[F - n_grid] == tag)
        return F;
    return invalid;
  }

  /// Calls f(F) for every extra field F of grid node @p I, in creation order.
  template <class F>
  void for_each_extra(const unsigned int I, const F &f) const
  {
    if (I >= first_extra.size())
      return;
    for (unsigned int K = first_extra[I]; K != invalid; K = next[K - n_grid])
      f(K);
  }

  /// The tag of an extra field (invalid for a grid node's own field).
  unsigned int tag_of(const unsigned int F) const
  {
    return F < n_grid ? invalid : tags[F - n_grid];
  }

  /// The grid node a field belongs to.
  unsigned int node_of(const unsigned int F) const
  {
    return F < n_grid ? F : owner[F - n_grid];
  }

private:
  unsigned int n_grid = 0;
  std::vector<unsigned int> first_extra;       // per grid node
  std::vector<unsigned int> owner, next, tags; // per extra field
};
} // namespace lme_mpm

#endif
