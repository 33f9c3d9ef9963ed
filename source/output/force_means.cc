#include <lme_mpm/output/force_means.h>

#include <algorithm>

namespace lme_mpm
{
template <int dim>
void ForceMeans<dim>::reset(const unsigned int n_bodies, const double window_time)
{
  peak_force.assign(n_bodies, 0.0);
  impulse.assign(n_bodies * dim, 0.0);
  impulse_time = 0;
  mean_force.assign(n_bodies, Tensor<1, dim>());
  window_force.assign(n_bodies, Tensor<1, dim>());
  window.reset(n_bodies * dim, window_time);
  flat.assign(n_bodies * dim, 0.0);
}

template <int dim>
void ForceMeans<dim>::book(const std::vector<Tensor<1, dim>> &f, const double dt)
{
  impulse_time += dt;
  for (unsigned int b = 0; b < f.size(); ++b)
    for (unsigned int d = 0; d < dim; ++d)
    {
      impulse[b * dim + d] += dt * f[b][d];
      flat[b * dim + d] = f[b][d];
    }
  window.book(flat, dt);
  for (unsigned int b = 0; b < f.size(); ++b)
  {
    for (unsigned int d = 0; d < dim; ++d)
      window_force[b][d] = window.mean(b * dim + d);
    peak_force[b] = std::max(peak_force[b], window_force[b].norm());
  }
}

template <int dim>
void ForceMeans<dim>::close_row(const std::vector<Tensor<1, dim>> &f)
{
  for (unsigned int b = 0; b < f.size(); ++b)
  {
    Tensor<1, dim> m = f[b];
    if (impulse_time > 0)
      for (unsigned int d = 0; d < dim; ++d)
        m[d] = impulse[b * dim + d] / impulse_time;
    mean_force[b] = m;
  }
  std::fill(impulse.begin(), impulse.end(), 0.0);
  impulse_time = 0;
}

template class ForceMeans<2>;
template class ForceMeans<3>;
} // namespace lme_mpm
