#ifndef LME_MPM_GRID_NODAL_FIELDS_H
#define LME_MPM_GRID_NODAL_FIELDS_H

#include <deal.II/base/tensor.h>

#include <lme_mpm/base/dealii.h>
#include <lme_mpm/base/parallel.h>
#include <lme_mpm/grid/field_layout.h>

#include <array>
#include <vector>

namespace lme_mpm
{
/**
 * The nodal arrays of one step, indexed by field (see FieldLayout): mass, momentum
 * and mass-weighted acceleration from the particles, the displacement rate of the
 * predictor, the forces and the accelerations of the corrector, and scratch for the
 * consistent-mass corrections. Only the active fields (those with mass this step)
 * are touched by nodal loops; the arrays are zero elsewhere, so empty regions of the
 * grid cost nothing per step.
 */
template <int dim>
struct NodalFields
{
  FieldLayout layout;

  std::vector<double> mass;
  std::vector<Tensor<1, dim>> momentum, mass_acceleration, rate, force, acceleration;
  /// Scratch of the consistent-mass corrections.
  std::vector<Tensor<1, dim>> rhs, scratch;
  /// Fields with mass this step, ascending.
  std::vector<unsigned int> active;

  /**
   * Zeroes what the last step wrote: the active fields and the fields of @p extra
   * grid nodes with all their extra fields (constraints write values on nodes that
   * may hold no mass). The layout may only have gained fields since (they are
   * appended); the arrays grow with it.
   */
  void clear(const std::vector<unsigned int> &extra)
  {
    const unsigned int n = layout.n_fields();
    if (mass.size() > n)
    {
      // The layout was rebuilt smaller (a resumed run): start from scratch.
      mass.assign(n, 0.0);
      for (auto *v : vector_fields())
        v->assign(n, Tensor<1, dim>());
      active.clear();
      return;
    }
    const auto zero = [&](const unsigned int I)
    {
      mass[I] = 0;
      for (auto *v : vector_fields())
        (*v)[I] = Tensor<1, dim>();
    };
    for_active(zero);
    for (const unsigned int I : extra)
      if (I < mass.size())
      {
        zero(I);
        layout.for_each_extra(I,
                              [&](const unsigned int F)
                              {
                                if (F < mass.size())
                                  zero(F);
                              });
      }
    active.clear();
    // A layout that gained fields (contact, a growing crack) keeps the old ones, so
    // what was written last step is cleared above; the new fields start at zero.
    if (mass.size() < n)
    {
      mass.resize(n, 0.0);
      for (auto *v : vector_fields())
        v->resize(n, Tensor<1, dim>());
    }
  }

  /// Collects the fields with mass after the particle-to-grid transfer.
  void collect_active()
  {
    // A scan of the mass array: a few hundred kilobytes even for large grids, far
    // less than clearing and updating every nodal array over the whole grid.
    const unsigned int n = mass.size();
    active.clear();
    for (unsigned int I = 0; I < n; ++I)
      if (mass[I] != 0)
        active.push_back(I);
  }

  /// Runs f(I) for every active field, in parallel.
  template <class F>
  void for_active(const F &f) const
  {
    parallel::for_range(active.size(),
                        [&](const std::size_t b, const std::size_t e)
                        {
                          for (std::size_t i = b; i < e; ++i)
                            f(active[i]);
                        });
  }

private:
  std::array<std::vector<Tensor<1, dim>> *, 7> vector_fields()
  {
    return {
        {&momentum, &mass_acceleration, &rate, &force, &acceleration, &rhs, &scratch}};
  }
};
} // namespace lme_mpm

#endif
