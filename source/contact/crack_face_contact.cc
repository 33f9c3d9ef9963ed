#include <lme_mpm/contact/crack_face_contact.h>

namespace lme_mpm
{
template <int dim>
CrackFaceContact<dim>::CrackFaceContact(const CrackSet<dim> &cracks,
                                        GridTransfer<dim> &transfer,
                                        const ParticleStore<dim> &particles)
    : cracks(cracks), transfer(transfer), particles(particles)
{
}

template <int dim>
std::uint8_t *CrackFaceContact<dim>::touched(const std::size_t n_particles)
{
  touches_crack.resize(n_particles);
  return touches_crack.data();
}

template <int dim>
void CrackFaceContact<dim>::on_rates(const double mass_tolerance)
{
  if (!cracks.face_contact() || cracks.n_crack_nodes() == 0)
    return;
  const NodalFields<dim> &nodes = transfer.nodes();
  const Connectivity<dim> &conn = transfer.connectivity();
  const unsigned int n_grid     = nodes.layout.n_grid_nodes();
  // Mass-weighted particle displacements of both fields of the crack nodes (the only
  // entries written and read), summed in the scatter's order.
  near.resize(cracks.n_crack_nodes());
  for (unsigned int J = 0; J < cracks.n_crack_nodes(); ++J)
    near[J] = body_fields ? body_fields->field_of_body(cracks.primary_of(J), cracks.body())
                          : cracks.primary_of(J);
  nodal_displacement.resize(nodes.mass.size());
  for (unsigned int J = 0; J < cracks.n_crack_nodes(); ++J)
  {
    if (near[J] != FieldLayout::invalid)
      nodal_displacement[near[J]] = Tensor<1, dim>();
    nodal_displacement[cracks.field_of(J)] = Tensor<1, dim>();
  }
  transfer.scatter(
      [&](const std::size_t p)
      {
        if (!touches_crack[p])
          return;
        const std::size_t o = p * conn.stride;
        const Tensor<1, dim> u =
            particles.mass[p] * (particles.position[p] - particles.reference_position[p]);
        // touches_crack marks only the cracked body's particles, so every field
        // summed here is one of its own (a crack node's near or far face, or a
        // field read by nobody).
        for (unsigned int k = 0; k < conn.n_nodes[p]; ++k)
        {
          const unsigned int K = conn.nodes[o + k];
          if (K >= n_grid || cracks.crack_node(K) != numbers::invalid_unsigned_int)
            nodal_displacement[K] += conn.N[o + k] * u;
        }
      });
  faces_closed.assign(cracks.n_crack_nodes(), 0);
  for (unsigned int J = 0; J < cracks.n_crack_nodes(); ++J)
  {
    const unsigned int I = near[J], K = cracks.field_of(J);
    if (I == FieldLayout::invalid)
      continue;
    const double mI = nodes.mass[I], mK = nodes.mass[K];
    faces_closed[J] =
        mI > mass_tolerance && mK > mass_tolerance &&
        (nodal_displacement[I] / mI - nodal_displacement[K] / mK) * cracks.normal_of(J) >=
            0;
  }
  std::vector<Tensor<1, dim>> &rate = transfer.nodes().rate;
  equalise(
      rate, [&](const unsigned int I) { return rate[I]; }, 1.0);
}

template <int dim>
void CrackFaceContact<dim>::on_accelerations(const ExplicitNewmark &newmark,
                                             const double dt)
{
  if (!cracks.face_contact() || cracks.n_crack_nodes() == 0)
    return;
  // The trial end-of-step velocity is what the corrector gives the field, lumped on
  // the node: (p + (1 - gamma) dt q) / m + gamma dt a, from the momentum p and the
  // mass-weighted acceleration q, which contact leaves alone (at gamma = 1/2: the rate
  // before on_rates plus gamma dt a). Making it equal on both fields makes the
  // particles, which take gamma dt sum_I N_I a_I from the nodes, lose the faces'
  // approach velocity; m_I da_I + m_K da_K = 0 keeps the momentum. Built from the rate
  // on_rates has equalised, it would show no approach, and the approach velocity,
  // with its kinetic energy, would stay in the particles.
  NodalFields<dim> &nodes = transfer.nodes();
  equalise(
      nodes.acceleration,
      [&](const unsigned int I) { return newmark.trial_velocity(nodes, I, dt); },
      newmark.gamma * dt);
}

template <int dim>
template <class Velocity>
void CrackFaceContact<dim>::equalise(std::vector<Tensor<1, dim>> &x,
                                     const Velocity &velocity, const double scale) const
{
  const std::vector<double> &mass = transfer.nodes().mass;
  for (unsigned int J = 0; J < cracks.n_crack_nodes(); ++J)
  {
    if (!faces_closed[J])
      continue;
    const unsigned int I = near[J], K = cracks.field_of(J);
    const Tensor<1, dim> &n = cracks.normal_of(J);
    const double mI = mass[I], mK = mass[K];
    const double vI = velocity(I) * n, vK = velocity(K) * n;
    if (!(vI > vK))
      continue;
    const double mean = (mI * vI + mK * vK) / (mI + mK);
    x[I] += ((mean - vI) / scale) * n;
    x[K] += ((mean - vK) / scale) * n;
  }
}

template class CrackFaceContact<2>;
template class CrackFaceContact<3>;
} // namespace lme_mpm
