#include <lme_mpm/contact/contact_forces.h>

namespace lme_mpm
{
template <int dim>
void ContactForces<dim>::sum_over_ranks()
{
  if (!ranks)
    return;
  std::vector<double> v;
  for (const auto &f : force)
    for (unsigned int d = 0; d < dim; ++d)
      v.push_back(f[d]);
  ranks->sum(v);
  for (unsigned int b = 0; b < force.size(); ++b)
    for (unsigned int d = 0; d < dim; ++d)
      force[b][d] = v[b * dim + d];
}

template class ContactForces<2>;
template class ContactForces<3>;
} // namespace lme_mpm
