#include <lme_mpm/base/input.h>
#include <lme_mpm/fracture/fracture_model.h>

namespace lme_mpm
{
namespace fracture
{
/**
 * Eigenerosion (Pandolfi & Ortiz 2012): a particle fails when the energy release
 * G_p = c eps (sum V_q W_q) / (sum V_q) over its epsilon-neighbourhood exceeds G_c
 * (c the 'Energy release factor', 1 by default);
 * it keeps its mass, loses its stress, and its stored energy counts as dissipated.
 */
template <int dim>
class Eigenerosion : public FractureModel<dim>
{
public:
  /// The entry of eigenerosion besides the shared ones.
  struct Entries
  {
    double factor = 1;
    void entries(EntryList &list)
    {
      list.add("Energy release factor", factor, "1", Patterns::Double(0),
               "Eigenerosion only: G_p = factor * eps * (volume-weighted mean energy "
               "density over the neighbourhood), > 0 (the normalising constant C_eps "
               "of the paper's eq. 13 is factor * eps). 1 makes a uniformly strained "
               "band one neighbourhood wide release its stored energy; at a sharp "
               "crack tip the asymptotic field needs about 7.2 (plane strain, nu = "
               "1/3): doc/validation_mode_i.md.");
    }
  };

  static void declare_parameters(ParameterHandler &prm)
  {
    declare_shared_fracture_parameters(prm);
    EntryList::declare<Entries>(prm);
  }

  Eigenerosion(ParameterHandler &prm, const FractureContext &c)
      : grid_spacing(c.grid_spacing)
  {
    const auto shared = SharedFractureEntries::parse(prm, c.section);
    C_eps             = shared.epsilon_factor;
    G_c               = shared.fracture_energy;
    factor            = EntryList::parse<Entries>(prm).factor;
    input::require_range(factor, 0, 1e6, true, c.section + "/Energy release factor");
  }

  std::string name() const override { return "eigenerosion"; }
  double epsilon(const double h) const override { return C_eps * h; }
  /// The mean keeps the neighbours within the particle's own epsilon.
  bool reads_rows_with_skin() const override { return true; }
  double row_reach(const double h, double) const override { return epsilon(h); }
  /// The volume-weighted mean density exceeds G_c / (factor eps) only if some
  /// neighbour's does; the largest eps gives the lowest bound.
  FractureTrigger trigger(const double h_largest) const override
  {
    return {FractureTrigger::Field::energy_density,
            G_c / (factor * C_eps * h_largest) * (1 - 1e-9)};
  }

  void update(ParticleStore<dim> &P, const Neighbourhood<dim> &nb,
              const FractureFields &F, const std::size_t begin, const std::size_t end,
              const unsigned int material_id) const override
  {
    for (std::size_t p = begin; p < end; ++p)
    {
      if (P.material_id[p] != material_id || P.failed[p] || !nb.has_row(p))
        continue;
      const double eps            = C_eps * F.spacing_of(p, grid_spacing);
      const double eps2           = eps * eps;
      const double release_length = factor * eps;
      double vw = 0, v = 0;
      for (auto q = nb.begin(p); q != nb.end(p); ++q)
        if (P.position[*q].distance_square(P.position[p]) <= eps2)
        {
          vw += P.initial_volume[*q] * F.energy_density[*q];
          v += P.initial_volume[*q];
        }
      if (release_length * vw > G_c * v)
      {
        P.failed[p] = 1;
        P.damage[p] = 1;
        P.dissipated[p] += P.initial_volume[p] * F.energy_density[p];
      }
    }
  }

private:
  double grid_spacing, C_eps = 0, G_c = 0, factor = 0;
};
} // namespace fracture
} // namespace lme_mpm

using lme_mpm::fracture::Eigenerosion;
LME_MPM_REGISTER_FRACTURE_MODEL(
    Eigenerosion, "eigenerosion",
    "a particle fails when its neighbourhood's energy release "
    "rate exceeds G_c.")
