#include <deal.II/base/symmetric_tensor.h>

#include <lme_mpm/base/bisection.h>
#include <lme_mpm/base/input.h>
#include <lme_mpm/base/tensor_tools.h>
#include <lme_mpm/fracture/fracture_model.h>
#include <lme_mpm/fracture/softening_law.h>
#include <lme_mpm/particles/damage_form.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <memory>

namespace lme_mpm
{
namespace fracture
{
/**
 * Eigensoftening (Navas et al. 2018): softening starts where the mass-weighted mean
 * of the max principal stress over the epsilon-neighbourhood (failed neighbours
 * count with zero stress, all with their mass) exceeds f_t, or with 'Onset = own
 * stress' where the particle's own does; the particle then damages with its max
 * principal strain beyond the onset value, spread over the band width.
 */
/// The entries of eigensoftening besides the shared ones, declared and read from this
/// one list.
struct EigensofteningEntries
{
  double tensile_strength = 3e6, critical_opening = 0, band_width = 0;
  std::string law, damage_rule, damage_form, onset;

  void entries(EntryList &list)
  {
    list.add("Tensile strength", tensile_strength, "3e6", Patterns::Double(0),
             "f_t (Pa), > 0: eigensoftening starts when the neighbourhood's "
             "mass-weighted max principal stress exceeds it.");
    list.add("Softening law", law, "linear",
             Patterns::Selection(SofteningLawRegistry::instance().pattern()),
             "Cohesive law of eigensoftening. " +
                 SofteningLawRegistry::instance().documentation());
    list.add("Critical opening", critical_opening, "0", Patterns::Double(0),
             "w_c (m) where the law reaches zero traction; 0: the law's own value "
             "(linear 2 G_F/f_t, bilinear 3.6 G_F/f_t).");
    list.add("Band width", band_width, "0", Patterns::Double(0),
             "h_eps (m), the width the crack opening is spread over by the 'crack band' "
             "and 'paper' rules; 0 ties it to the band a crack localises in on the "
             "grid: the local grid spacing h (the shortest side of the particle's cell "
             "at t = 0) times the shape functions' band in cells, 1 for linear "
             "functions and wider for smoother ones, measured from the functions at "
             "the start for a crack along the grid lines (doc/theory.md). Not used by "
             "'measured band'.");
    list.add("Damage rule", damage_rule, "crack band",
             Patterns::Selection("crack band|measured band|paper"),
             "'crack band': the damage makes the particle's max principal stress follow "
             "the cohesive law at the opening of a band h_eps wide, so the band "
             "dissipates G_F per unit area where the crack localises in that width; "
             "'measured band': the same law at the opening of the band the particle "
             "lies in, its particles' damaged strains integrated across it along the "
             "max principal strain, G_F per unit area at any angle to the grid (the "
             "integral sees the particle's own body only); 'paper': chi = 1 - g((eps_I "
             "- eps_onset) h_eps), the draft's eq. 22 (dissipates more than G_F: "
             "doc/theory.md).");
    list.add("Onset", onset, "neighbourhood mean",
             Patterns::Selection("neighbourhood mean|own stress"),
             "When a particle starts to soften. 'neighbourhood mean' (the paper's): the "
             "mass-weighted mean of the max principal stress over its "
             "epsilon-neighbourhood exceeds f_t (failed neighbours count with zero "
             "stress; with 'crack oriented' damage the mean is over the uncracked "
             "neighbours). 'own stress': its own max principal stress exceeds f_t, the "
             "onset of the crack band model (Bazant and Oh 1983): a notch tip starts "
             "softening when its stress reaches the strength, and the process zone "
             "grows before the peak as in a cohesive crack; the damage rule keeps the "
             "dissipation at G_F per unit crack area (doc/theory.md).");
    list.add("Damage form", damage_form, "isotropic",
             Patterns::Selection("isotropic|crack oriented"),
             "What the damage acts on. 'isotropic': the whole stress, (1 - chi) sigma, "
             "compression included (the paper's form). 'crack oriented': at onset the "
             "particle fixes its crack normal n (the max principal direction of its "
             "neighbourhood's mean stress); the law then follows the strain and stress "
             "across the crack, and the damage acts on the normal traction n . sigma "
             ". n while it opens the crack and on the shear traction on the crack "
             "plane (shear retention 1 - chi), while compression across a closed crack "
             "and the stress parallel to it are carried undamaged (doc/theory.md).");
  }
};

template <int dim>
class Eigensoftening : public FractureModel<dim>
{
public:
  static void declare_parameters(ParameterHandler &prm)
  {
    declare_shared_fracture_parameters(prm);
    EntryList::declare<EigensofteningEntries>(prm);
    // A law with entries of its own keeps them in a subsection named after it.
    SofteningLawRegistry::instance().declare_all(prm);
  }

  Eigensoftening(ParameterHandler &prm, const FractureContext &c)
      : grid_spacing(c.grid_spacing), thickness(c.dim == 2 ? c.thickness : 1.0)
  {
    const auto shared = SharedFractureEntries::parse(prm, c.section);
    const auto in     = EntryList::parse<EigensofteningEntries>(prm);
    C_eps             = shared.epsilon_factor;
    SofteningContext sc;
    sc.tensile_strength = in.tensile_strength;
    sc.fracture_energy  = shared.fracture_energy;
    sc.critical_opening = in.critical_opening;
    sc.section          = c.section;
    input::require_range(sc.tensile_strength, 0, 1e300, true,
                         c.section + "/Tensile strength");
    f_t           = sc.tensile_strength;
    law           = SofteningLawRegistry::instance().create(in.law, prm, sc);
    w_c           = law->critical_opening();
    band_width    = in.band_width;
    paper_rule    = in.damage_rule == "paper";
    measured_band = in.damage_rule == "measured band";
    oriented      = in.damage_form == "crack oriented";
    own_onset     = in.onset == "own stress";
    coupling      = c.lame_coupling;
    // A band wider than M / (f_t max|g'|) snaps back: the softening branch cannot be
    // followed. Checked with the P-wave modulus here and per particle at onset.
    AssertThrow(
        !(measured_band && band_width > 0),
        ExcBadInput(c.section + "/Band width",
                    "must be 0 with 'Damage rule = measured band', which measures "
                    "the band instead of setting its width"));
    if (band_width > 0 && !paper_rule && c.p_wave_modulus > 0)
    {
      const double limit = c.p_wave_modulus / (f_t * law->max_slope());
      std::ostringstream msg;
      msg << "'" << c.section << "/Band width' = " << band_width
          << " m is beyond the snap-back limit M / (f_t max|g'|) = " << limit
          << " m (about 2 E G_F / f_t^2 for linear softening), from the P-wave modulus "
          << "M = " << c.p_wave_modulus << " Pa (the material's elastic entries), '"
          << c.section << "/Tensile strength' = " << f_t
          << " Pa and the softening law's critical opening w_c = " << w_c << " m";
      AssertThrow(band_width < limit, ExcBadInput(c.section + "/Band width", msg.str()));
    }
  }

  std::string name() const override { return "eigensoftening"; }
  double epsilon(const double h) const override { return C_eps * h; }
  /// Far enough to hold a crack band (band_cells h either side) for its opening.
  bool reads_crack_strains() const override { return measured_band; }
  /// Crack-oriented damage takes its normal from the neighbourhood's mean stress.
  bool reads_stress_tensors() const override { return oriented; }
  bool reads_strength_factors() const override { return true; }
  /// Every read of a row tests the distance (band_opening() against the row's radius).
  bool reads_rows_with_skin() const override { return true; }
  double search_radius(const double h) const override
  {
    return std::max(C_eps, measured_band ? band_cells : 0.0) * h;
  }
  /// The sums reach search_radius(h); band_opening()'s line reaches
  /// (reach + line_slack) h along the crack direction and line_half_width h off it,
  /// so within (reach + line_slack + line_half_width) h.
  double row_reach(const double h, const double band_reach_cells) const override
  {
    return std::max(search_radius(h),
                    (band_reach_cells + (line_slack + line_half_width)) * h);
  }
  /// The mass-weighted mean exceeds f_t only if some neighbour's stress does (failed
  /// neighbours count with zero). The margin covers the rounding of the sums.
  FractureTrigger trigger(double) const override
  {
    return {FractureTrigger::Field::max_principal_stress, f_t * (1 - 1e-9)};
  }

  void update(ParticleStore<dim> &P, const Neighbourhood<dim> &nb,
              const FractureFields &F, const std::size_t begin, const std::size_t end,
              const unsigned int material_id) const override
  {
    unsigned long snapped = 0;
    for (std::size_t p = begin; p < end; ++p)
    {
      if (P.material_id[p] != material_id || P.failed[p])
        continue;
      // An intact particle without a row has no seed near: it cannot reach onset, and
      // costs no more (most particles, most steps).
      if (P.onset_strain[p] == 0 && !nb.has_row(p))
        continue;
      // Lengths from the particle's own cell: on a graded grid a crack in coarse cells
      // spreads over a wider band than one in fine cells.
      const double h_p  = F.spacing_of(p, grid_spacing);
      const double eps  = C_eps * h_p;
      const double eps2 = eps * eps;
      if (P.onset_strain[p] == 0)
      {
        if (!reaches_onset(P, nb, F, p, eps2))
          continue;
        // Onset needs the particle itself in tension, so that its modulus is known
        // (its drive is found only where the mean has reached the strength).
        const auto [eps_I, sig_I] = damage_drive(P, p, F.max_principal_stress[p]);
        if (!(eps_I > 0 && sig_I > 0))
          continue;
        if (!oriented)
        {
          P.onset_strain[p] = eps_I;
          P.onset_stress[p] = sig_I;
          continue;
        }
        // The crack opens across the max principal direction of the neighbourhood's
        // mean stress, and its law starts from the strain and stress across it.
        const Tensor<1, dim> normal = onset_normal(P, nb, F, p, eps2);
        const double eps_n          = normal * (P.strain[p] * normal),
                     sig_n          = normal * (P.stress[p] * normal);
        if (eps_n > 0 && sig_n > 0)
        {
          P.onset_strain[p]   = eps_n;
          P.onset_stress[p]   = sig_n;
          P.crack_normal[p]   = normal;
          P.crack_coupling[p] = coupling;
        }
        continue;
      }
      const auto [eps_I, sig_I] = damage_drive(P, p, F.max_principal_stress[p]);
      const double h = band_width > 0 ? band_width : F.band_cells_of(P.body_id[p]) * h_p;
      const double strain_beyond = eps_I - P.onset_strain[p];
      double chi_new             = 0;
      if (measured_band)
        chi_new = band_damage(P, nb, F, p, h_p, eps_I, sig_I,
                              std::pow(std::max(C_eps, band_cells) * h_p, 2), snapped);
      else if (paper_rule)
        chi_new =
            1 - law->traction_ratio(std::max(0.0, strain_beyond) * h * P.strength[p]);
      else
      {
        // The cohesive law starts at the particle's own stress at onset s0 when that is
        // below f_t (the neighbourhood's mean reached f_t, its own need not have): peak
        // s0, openings scaled by f_t / s0, so that the area under it, the energy per
        // unit crack area, stays G_F. A particle above f_t at onset (beside a notch
        // tip, s0 reaches 3 f_t) drops to f_t at once, the drop's energy booked by the
        // secant damage, and then follows the law itself: a law scaled up to s0 would
        // be (s0 / f_t)^2 times steeper, beyond what the band can follow.
        // A particle of strength k f_t (Strength variability) caps s0 at k f_t; the law
        // keeps G_F, its openings scaled by f_t / s0 as below.
        const double s0 = law_peak(P.onset_stress[p], P.strength[p]), r = s0 / f_t;
        const double M = P.onset_stress[p] / P.onset_strain[p];
        if (1 / h <= s0 * r * law->max_slope() / M)
        {
          chi_new            = 1; // beyond the snap-back limit: breaks at once
          P.crack_opening[p] = 1;
          ++snapped;
        }
        else
        {
          const double w_end = w_c / r;
          const double own   = opening(strain_beyond, h, M, s0, r, w_end) / w_end;
          P.crack_opening[p] = own;
          const double w     = band_opening(P, nb, F, p, own, h_p) * w_end;
          const double s     = s0 * law->traction_ratio(r * w);
          chi_new            = w >= w_end ? 1.0 : (sig_I > s ? 1 - s / sig_I : 0.0);
        }
      }
      const double chi_old = P.damage[p];
      const double chi     = std::min(1.0, std::max(chi_old, chi_new));
      if (chi > chi_old)
      {
        // Secant damage: losing d chi of the damageable energy dissipates it.
        P.dissipated[p] +=
            (chi - chi_old) * P.initial_volume[p] * damageable_energy_density(P, p);
        P.damage[p] = chi;
      }
      // An oriented crack fully open still carries compression across it and the
      // stress parallel to it: it is not failed.
      if (chi >= 1 && !has_crack_normal(P, p))
        P.failed[p] = 1;
    }
    if (snapped)
      snap_back_count += snapped;
  }

  std::vector<std::pair<std::string, double>> statistics() const override
  {
    return {{"snap_back_particles", double(snap_back_count.load())}};
  }

private:
  /// Whether intact particle @p p starts to soften (the entry 'Onset').
  bool reaches_onset(const ParticleStore<dim> &P, const Neighbourhood<dim> &nb,
                     const FractureFields &F, const std::size_t p,
                     const double eps2) const
  {
    const double strength = f_t * P.strength[p];
    if (own_onset)
      return F.max_principal_stress[p] > strength;
    // With oriented damage a cracked neighbour's stress follows its crack's law,
    // not the field the onset samples: the mean is over the intact ones.
    double ms = 0, m = 0;
    for (auto q = nb.begin(p); q != nb.end(p); ++q)
      if (P.position[*q].distance_square(P.position[p]) <= eps2 &&
          !(oriented && F.cracked[*q]))
      {
        ms += P.mass[*q] * F.max_principal_stress[*q];
        m += P.mass[*q];
      }
    return ms > strength * m;
  }

  /**
   * The damage of softening particle @p p from the opening of the crack band it lies
   * in. Across a band the crack strains of its particles (the part of the max
   * principal strain their damage does not carry) integrate to the crack's opening w;
   * every particle of the band follows the cohesive law at that w, so the band loses
   * its traction together and dissipates G_F per unit crack area, however many
   * particles across it soften and however it crosses the grid. The integral runs
   * along p's max principal strain direction n over the particles of its
   * neighbourhood, each weighted by a hat kernel of its distance from the line
   * through p (half-width h_p) and divided by the share of that line's neighbourhood
   * the body fills (so a band that ends at a free surface is measured right). p's own
   * crack strain enters implicitly: w = W + a (eps_I - eps_I t(w) / sigma_I), with W
   * the others' part (from the snapshot) and a p's own weight.
   */
  double band_damage(ParticleStore<dim> &P, const Neighbourhood<dim> &nb,
                     const FractureFields &F, const std::size_t p, const double h_p,
                     const double eps_I, const double sig_I, const double eps2,
                     unsigned long &snapped) const
  {
    // The law of peak s0 (at most the particle's strength k f_t) and energy G_F: its
    // openings scaled by f_t / s0 (1 / k for a particle that starts at its strength).
    const double s0 = law_peak(P.onset_stress[p], P.strength[p]), r = s0 / f_t,
                 w_end = w_c / r;
    if (!(eps_I > 0 && sig_I > 0) || !nb.has_row(p))
      return 0;
    const Tensor<1, dim> n = crack_direction(P, p);
    const double rho = h_p, rho2 = rho * rho;
    const auto kernel = [&](const double t2)
    {
      const double d = std::sqrt(t2) / rho;
      return dim == 2 ? (1 - d) / rho : 3 * (1 - d) / (M_PI * rho2);
    };
    double band = 0, coverage = 0;
    for (auto q = nb.begin(p); q != nb.end(p); ++q)
    {
      const Tensor<1, dim> d = P.position[*q] - P.position[p];
      const double r2        = d.norm_square();
      if (r2 > eps2)
        continue;
      const double along = d * n, t2 = r2 - along * along;
      if (t2 >= rho2)
        continue;
      const double weight = P.initial_volume[*q] / thickness * kernel(t2);
      // The body's share of the disc around p, with a hat along n too.
      if (std::abs(along) < rho)
        coverage += weight * (1 - std::abs(along) / rho) / rho;
      if (*q != p)
        band += weight * F.crack_strain[*q];
    }
    const double share = std::min(1.0, coverage);
    if (!(share > 0))
      return 0;
    const double others = band / share;
    const double a      = P.initial_volume[p] / thickness * kernel(0) / share;
    const auto traction = [&](const double w) { return s0 * law->traction_ratio(r * w); };
    double w            = others;
    if (others < w_end)
    {
      // f(w) = others + a eps_I (1 - t(w) / sigma_I) - w, decreasing below the
      // particle's own snap-back limit.
      const auto f = [&](const double x)
      { return others + a * eps_I * (1 - traction(x) / sig_I) - x; };
      if (a * eps_I * s0 * r * law->max_slope() / sig_I >= 1)
        ++snapped;
      if (f(others) > 0)
      {
        double lo = others, hi = std::min(w_end, others + a * eps_I);
        if (f(hi) > 0)
          lo = hi;
        bisect(lo, hi, 60, [&](const double x) { return f(x) > 0; });
        w = 0.5 * (lo + hi);
      }
    }
    P.crack_opening[p] = w;
    if (w >= w_end * (1 - 1e-12))
      return 1;
    const double t = traction(w);
    return sig_I > t ? 1 - t / sig_I : 0.0;
  }

  /**
   * The opening of the band particle @p p lies in, as a fraction of p's critical
   * opening w_c f_t / s0_p: the largest of its own (@p own) and those of the softening
   * particles across the band from it, on the line through it along its max principal
   * strain (within a quarter of its cell size @p h_p of that line) and no farther than
   * the shape functions' reach (crack_band()). Smooth functions spread a crack's jump
   * over particles up to two cells from it, each straining by a share of the jump; with
   * its own opening alone each would go on carrying stress across a band whose middle
   * has failed (stress locking) and dissipate more as the crack keeps opening. With
   * the band's opening they lose their traction together, once. Particles beyond the
   * reach do not share it, so the band still localises; particles along the crack
   * are off the line, so a crack does not run ahead of its tip.
   */
  double band_opening(const ParticleStore<dim> &P, const Neighbourhood<dim> &nb,
                      const FractureFields &F, const std::size_t p, const double own,
                      const double h_p) const
  {
    const double reach = F.band_reach_of(P.body_id[p]) * h_p;
    if (reach <= 0 || own >= 1 || !nb.has_row(p))
      return own;
    // The reach is a distance between particle positions at t = 0; the slack lets
    // particles that have moved a little still count.
    const double along_max = reach + line_slack * h_p,
                 off2      = line_half_width * line_half_width * h_p * h_p,
                 within2   = nb.radius() * nb.radius();
    Tensor<1, dim> n;
    bool have_normal    = false;
    double band         = own;
    const double peak_p = law_peak(P.onset_stress[p], P.strength[p]);
    for (auto q = nb.begin(p); q != nb.end(p); ++q)
    {
      if (F.crack_opening[*q] <= 0)
        continue;
      // The band shares one opening w, not one fraction of a critical opening: q's
      // fraction is of its own w_end = w_c f_t / s0_q, p's of w_c f_t / s0_p (s0 the
      // law's peak, law_peak()), which differ where particles start below f_t.
      const double shared =
          F.crack_opening[*q] * peak_p / law_peak(P.onset_stress[*q], P.strength[*q]);
      if (shared <= band)
        continue;
      if (!have_normal) // only once a neighbour is more open than p
        n = crack_direction(P, p), have_normal = true;
      const Tensor<1, dim> d = P.position[*q] - P.position[p];
      const double along     = d * n;
      // The line reaches as far as the row's radius, not its skin.
      const double d2 = d.norm_square();
      if (std::abs(along) <= along_max && d2 - along * along <= off2 && d2 <= within2)
        band = std::min(1.0, shared);
    }
    return band;
  }

  /**
   * Crack opening w for a band strain beyond onset: the band strain is the elastic
   * change of the cohesive stress plus the opening spread over h,
   * d eps = s0 (g(r w) - 1) / M + w / h, increasing in w below the snap-back limit
   * (the law of peak s0 = r f_t that ends at w_end = w_c / r).
   */
  double opening(const double strain_beyond, const double h, const double M,
                 const double s0, const double r, const double w_end) const
  {
    if (strain_beyond <= 0)
      return 0;
    auto F = [&](const double w)
    { return s0 * (law->traction_ratio(r * w) - 1) / M + w / h - strain_beyond; };
    if (F(w_end) <= 0)
      return w_end;
    // F' >= 1/h - s0 r max|g'| / M, positive inside the snap-back limit (update()
    // breaks the particle at once beyond it). Rounding of F: a few ulps of each term,
    // with g within a few ulps of 1 (the built-in laws); 64 ulps are allowed.
    const double slope = (1 / h - s0 * r * law->max_slope() / M) * (1 - 1e-9);
    const auto error   = [&](const double w)
    {
      return 64 * std::numeric_limits<double>::epsilon() *
             (s0 / M + std::abs(w) / h + std::abs(strain_beyond));
    };
    double lo = 0, hi = w_end;
    bisect_increasing(lo, hi, 60, F, slope, error);
    return 0.5 * (lo + hi);
  }

  /// The direction across particle @p p's crack: its oriented crack's normal, or its
  /// max principal strain direction.
  static Tensor<1, dim> crack_direction(const ParticleStore<dim> &P, const std::size_t p)
  {
    return has_crack_normal(P, p) ? P.crack_normal[p]
                                  : eigenvectors(P.strain[p])[0].second;
  }

  /**
   * The normal of the crack particle @p p opens at onset: the max principal direction
   * of the mass-weighted mean stress over its epsilon-neighbourhood (radius squared
   * @p eps2; the stresses the onset mean reads, FractureFields::stress), the mean whose
   * max principal value reached f_t.
   */
  static Tensor<1, dim> onset_normal(const ParticleStore<dim> &P,
                                     const Neighbourhood<dim> &nb,
                                     const FractureFields &F, const std::size_t p,
                                     const double eps2)
  {
    constexpr unsigned int n_c = SymmetricTensor<2, dim>::n_independent_components;
    SymmetricTensor<2, dim> mean;
    for (auto q = nb.begin(p); q != nb.end(p); ++q)
      if (P.position[*q].distance_square(P.position[p]) <= eps2 && !F.cracked[*q])
      {
        unsigned int c = 0;
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = i; j < dim; ++j)
            mean[i][j] += P.mass[*q] * F.stress[*q * n_c + c++];
      }
    return eigenvectors(mean)[0].second;
  }

  /// The peak of a particle's cohesive law from its stress at onset: that stress,
  /// but no more than its strength, @p strength times f_t (see update()).
  double law_peak(const double onset_stress, const double strength) const
  {
    return std::min(onset_stress, strength * f_t);
  }

  double grid_spacing, thickness, C_eps = 0, f_t = 0, w_c = 0, band_width = 0;
  /// Crack-oriented damage, and lambda / M of the material.
  bool oriented   = false;
  double coupling = 0;
  /// How far either side of a particle its crack band's opening is summed, in cells.
  static constexpr double band_cells = 3;
  /// band_opening()'s line, in cells: how far beyond the band's reach it extends along
  /// the crack direction (a tenth of a cell), and its half width across (a quarter).
  static constexpr double line_slack = 0.1, line_half_width = 0.25;
  bool paper_rule = false, measured_band = false;
  /// Onset on the particle's own stress rather than its neighbourhood's mean.
  bool own_onset = false;
  std::unique_ptr<SofteningLaw> law;
  mutable std::atomic<unsigned long> snap_back_count{0};
};
} // namespace fracture
} // namespace lme_mpm

using lme_mpm::fracture::Eigensoftening;
LME_MPM_REGISTER_FRACTURE_MODEL(
    Eigensoftening, "eigensoftening",
    "strength onset on the neighbourhood-averaged (or the particle's "
    "own) max principal stress, then cohesive softening through a "
    "band width.")
