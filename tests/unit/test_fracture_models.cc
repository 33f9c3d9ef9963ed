// Fracture models and softening laws on particles set up by hand.
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/parameter_handler.h>

#include <gtest/gtest.h>

#include <lme_mpm/fracture/crack_set.h>
#include <lme_mpm/fracture/fracture_coupling.h>
#include <lme_mpm/fracture/fracture_model.h>
#include <lme_mpm/fracture/neighbourhood.h>
#include <lme_mpm/fracture/softening_law.h>
#include <lme_mpm/materials/material_set.h>

#include "sorted_particles.h"
#include "test_helpers.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <iostream>
#include <random>

using namespace lme_mpm;

namespace
{
/// Sets @p grid to one cell around the one particle of @p P, located and sorted as a
/// neighbourhood needs them; returns @p P.
const ParticleStore<2> &sorted_on_one_cell(ParticleStore<2> &P, BackgroundGrid<2> &grid)
{
  grid.reinit(P.position[0] + Point<2>(-0.5, -0.5), {{{1.0}, {1.0}}});
  P.cell[0] = 0;
  P.sort_by_cell(1);
  return P;
}

/// Eigensoftening (f_t = 3 MPa, the default eps = 2 h) on material 1, coupled to a
/// uniform grid of cells h = 0.01 from @p lower, @p nx cells along x and 20 along y.
struct EigensofteningOnAGrid
{
  EigensofteningOnAGrid(const Point<2> &lower, const unsigned int nx,
                        const std::string &onset)
  {
    ParameterHandler prm;
    MaterialSet<2>::declare_parameters(prm, 1);
    FractureCoupling<2>::declare_parameters(prm, 1);
    prm.parse_input_from_string("subsection Material 1\n"
                                "  set Density = 2400\n"
                                "  subsection Fracture\n"
                                "    set Model            = eigensoftening\n"
                                "    set Tensile strength = 3e6\n"
                                "    set Onset            = " +
                                onset +
                                "\n"
                                "  end\n"
                                "end\n");
    materials.parse_parameters(prm, 1, false);
    grid.reinit(lower, {{std::vector<double>(nx, 0.01), std::vector<double>(20, 0.01)}});
    coupling.parse_parameters(prm, materials, grid, 1);
  }

  MaterialSet<2> materials;
  BackgroundGrid<2> grid;
  FractureCoupling<2> coupling;
};
} // namespace

TEST(SofteningLaws, AreaEqualsFractureEnergy)
{
  for (const char *name : {"linear", "bilinear", "exponential"})
  {
    SofteningContext c;
    c.tensile_strength = 3e6;
    c.fracture_energy  = 100;
    ParameterHandler prm;
    const auto law   = SofteningLawRegistry::instance().create(name, prm, c);
    const double w_c = law->critical_opening();
    EXPECT_DOUBLE_EQ(law->traction_ratio(0), 1.0) << name;
    EXPECT_EQ(law->traction_ratio(w_c), 0.0) << name;
    double area = 0, previous = 1;
    const unsigned int n = 200000;
    for (unsigned int i = 0; i < n; ++i)
    {
      const double g = law->traction_ratio((i + 0.5) * w_c / n);
      EXPECT_LE(g, previous) << name;
      previous = g;
      area += g * w_c / n;
    }
    // Exponential: the tail beyond g = 1e-3 is cut (0.1 % of G_F).
    const double expected = std::string(name) == "exponential" ? 0.999 : 1.0;
    EXPECT_NEAR(area * c.tensile_strength / c.fracture_energy, expected, 1e-4) << name;
  }
}

TEST(FractureParameters, EachModelDeclaresWhatItReads)
{
  for (const std::string name : {"eigenerosion", "eigensoftening"})
  {
    const auto *entry = FractureModelRegistry<2>::instance().find(name);
    ASSERT_TRUE(entry && entry->declare) << name;
    EXPECT_FALSE(entry->own_subsection) << name; // straight into "Material N/Fracture"
    ParameterHandler prm;
    entry->declare(prm);
    EXPECT_EQ(prm.get("Epsilon factor"), "2") << name; // the shared entries
    EXPECT_EQ(prm.get("Fracture energy"), "100") << name;
  }
  // What declare_shared_fracture_parameters() relies on: deal.II takes a second
  // declaration of an entry, which replaces the first one, value included.
  ParameterHandler prm;
  prm.declare_entry("Entry", "1", Patterns::Double(0), "first");
  prm.set("Entry", "5");
  prm.declare_entry("Entry", "2", Patterns::Double(0), "second");
  EXPECT_EQ(prm.get("Entry"), "2");
  // So the shared entries, declared by both built-in models and once more at the end,
  // come out as if declared once.
  ParameterHandler once, twice;
  declare_fracture_parameters<2>(once);
  declare_fracture_parameters<2>(twice);
  declare_fracture_parameters<2>(twice);
  std::ostringstream a, b;
  once.print_parameters(a, ParameterHandler::PRM);
  twice.print_parameters(b, ParameterHandler::PRM);
  EXPECT_EQ(a.str(), b.str());
  EXPECT_NE(a.str().find("Energy release factor"), std::string::npos);
  EXPECT_NE(a.str().find("Tensile strength"), std::string::npos);
}

TEST(Eigensoftening, UnloadingDoesNotHeal)
{
  ParameterHandler prm;
  declare_fracture_parameters<2>(prm);
  prm.set("Model", "eigensoftening");
  prm.set("Tensile strength", "3e6");
  prm.set("Fracture energy", "50");
  prm.set("Band width", "0.01");
  FractureContext fc;
  fc.grid_spacing   = 0.01;
  fc.p_wave_modulus = 30e9;
  fc.section        = "test";
  const auto model =
      FractureModelRegistry<2>::instance().create("eigensoftening", prm, fc);

  ParticleStore<2> P;
  P.add(Point<2>(0, 0), 1.0, 1.0, 0, 0);
  BackgroundGrid<2> grid;
  Neighbourhood<2> nb;
  nb.build(sorted_on_one_cell(P, grid), grid, model->epsilon(0.01));
  FractureFields F;
  auto load = [&](const double strain)
  {
    P.strain[0]            = SymmetricTensor<2, 2>();
    P.strain[0][0][0]      = strain;
    P.stress[0]            = 30e9 * P.strain[0];
    F.max_principal_stress = {P.stress[0][0][0]};
    F.energy_density       = {0.5 * (P.stress[0] * P.strain[0])};
    model->update(P, nb, F, 0, 1, 0);
    return P.damage[0];
  };
  EXPECT_EQ(load(0.9e-4), 0.0);
  EXPECT_EQ(P.onset_strain[0], 0.0); // below f_t: no onset
  load(1.01e-4);                     // onset
  EXPECT_GT(P.onset_strain[0], 0.0);
  const double d1 = load(1.2e-4);
  EXPECT_GT(d1, 0.0);
  EXPECT_LT(d1, 1.0);
  // The effective stress follows the cohesive law: (1 - chi) sigma = f_t g(w) < f_t.
  EXPECT_LT((1 - d1) * 30e9 * 1.2e-4, 3.03e6);
  const double d_unload = load(0.5e-4); // unloading keeps the damage
  EXPECT_EQ(d_unload, d1);
  const double diss = P.dissipated[0];
  EXPECT_GT(diss, 0);
  const double d2 = load(1.5e-4); // reloading past the old strain damages further
  EXPECT_GT(d2, d1);
  EXPECT_GT(P.dissipated[0], diss);
  load(1e-2); // far beyond w_c: fully failed
  EXPECT_EQ(P.damage[0], 1.0);
  EXPECT_EQ(P.failed[0], 1);
}

TEST(Eigensoftening, DissipatesFractureEnergyWhateverItsOwnStressAtOnset)
{
  // Onset is triggered by the neighbourhood's mean stress, so a particle may start
  // softening with its own stress s0 above or below f_t. One particle of a band
  // h = 0.05 m wide (volume h per unit crack area) pulled until it fails dissipates
  // G_F per unit area through its cohesive law. Below f_t the law starts at s0 (its
  // openings scaled so that its area stays G_F; anchored at f_t it dissipated 0.94 G_F
  // at 0.8 f_t). Above f_t the stress drops to f_t at onset and the law is f_t's own:
  // the drop dissipates (s0^2 - f_t^2) / (2 E) per unit volume besides G_F (1.19 G_F
  // in all at 1.5 f_t), where a law scaled up to s0 would be (s0 / f_t)^2 times steeper
  // and snap back in a band of the scenes' width.
  const double E = 30e9, f_t = 3e6, G_F = 50, h = 0.05;
  ParameterHandler prm;
  declare_fracture_parameters<2>(prm);
  prm.set("Model", "eigensoftening");
  prm.set("Tensile strength", std::to_string(f_t));
  prm.set("Fracture energy", std::to_string(G_F));
  prm.set("Band width", std::to_string(h));
  FractureContext fc;
  fc.grid_spacing   = 0.01;
  fc.p_wave_modulus = E;
  fc.section        = "test";
  for (const char *name : {"linear", "exponential"})
    for (const double ratio : {0.8, 1.0, 1.5})
    {
      prm.set("Softening law", name);
      const auto model =
          FractureModelRegistry<2>::instance().create("eigensoftening", prm, fc);
      ParticleStore<2> P;
      P.add(Point<2>(0, 0), 1.0, h, 0, 0);
      BackgroundGrid<2> grid;
      Neighbourhood<2> nb;
      nb.build(sorted_on_one_cell(P, grid), grid, model->epsilon(0.01));
      const double s0   = ratio * f_t;
      P.onset_strain[0] = s0 / E;
      P.onset_stress[0] = s0;
      FractureFields F;
      // Strain steps of 1e-3 eps_0: the secant dissipation sum, first order in the
      // step, is then within 0.06 %.
      const double step = 1e-3 * s0 / E;
      for (double strain = s0 / E; !P.failed[0] && strain < 1; strain += step)
      {
        P.strain[0]            = SymmetricTensor<2, 2>();
        P.strain[0][0][0]      = strain;
        P.stress[0]            = E * P.strain[0];
        F.max_principal_stress = {P.stress[0][0][0]};
        F.energy_density       = {0.5 * (P.stress[0] * P.strain[0])};
        model->update(P, nb, F, 0, 1, 0);
      }
      ASSERT_TRUE(P.failed[0]) << name << " s0/f_t = " << ratio;
      std::cout << name << " law, s0/f_t = " << ratio
                << ": dissipated / G_F = " << P.dissipated[0] / G_F << "\n";
      const double drop = ratio > 1 ? (s0 * s0 - f_t * f_t) / (2 * E) * h : 0.0;
      EXPECT_NEAR(P.dissipated[0] / (G_F + drop), 1.0, 0.01)
          << name << " s0/f_t = " << ratio;
    }
}

TEST(Eigensoftening, OnsetAveragesOverTheParticlesOwnBodyOnly)
{
  // A platen (body 0) pressed against a specimen (body 1), the two touching along
  // x = 0: the platen at ten times f_t, the specimen in tension below it. Within the
  // neighbourhood (eps = 2 h = 0.02) the mixed average would exceed f_t; the
  // specimen's own does not, so only the platen's particles reach onset.
  EigensofteningOnAGrid on_grid(Point<2>(-0.1, -0.1), 20, "neighbourhood mean");
  auto &grid     = on_grid.grid;
  auto &coupling = on_grid.coupling;

  ParticleStore<2> store;
  for (unsigned int i = 0; i < 8; ++i)
    for (unsigned int j = 0; j < 8; ++j)
    {
      const unsigned int body = i < 4 ? 0 : 1;
      const auto p = store.add(Point<2>(0.0025 + 0.005 * (double(i) - 4), 0.005 * j), 1.0,
                               1.0, 0, body);
      store.stress[p][0][0] = body == 0 ? 30e6 : 1e6;
      store.strain[p][0][0] = store.stress[p][0][0] / 30e9;
    }
  lme_mpm_test::sort_by_grid_cells(store, grid);
  coupling.update(store);
  for (std::size_t p = 0; p < store.size(); ++p)
    if (store.body_id[p] == 0)
      EXPECT_GT(store.onset_strain[p], 0.0) << "platen particle " << p;
    else
      EXPECT_EQ(store.onset_strain[p], 0.0)
          << "specimen particle " << p << " at x = " << store.position[p][0];
}

namespace
{
/**
 * A hot spot: particles on a 5 mm lattice, one at 3 f_t (a notch tip's own stress)
 * among neighbours at 0.2 f_t, and one at 0.9 f_t among neighbours at 2 f_t, far
 * apart. Returns which particles reached onset with the entry 'Onset' = @p onset.
 */
std::vector<bool> onsets_of_hot_spots(const std::string &onset)
{
  EigensofteningOnAGrid on_grid(Point<2>(-0.2, -0.1), 40, onset);
  auto &grid     = on_grid.grid;
  auto &coupling = on_grid.coupling;

  ParticleStore<2> store;
  const Point<2> cold_tip(-0.1, 0), hot_ring(0.1, 0);
  for (int i = -4; i <= 4; ++i)
    for (int j = -4; j <= 4; ++j)
      for (const Point<2> &centre : {cold_tip, hot_ring})
      {
        const bool at_centre = i == 0 && j == 0;
        const bool tip       = centre == cold_tip;
        const double s = tip ? (at_centre ? 9e6 : 0.6e6) : (at_centre ? 2.7e6 : 6e6);
        const auto p = store.add(centre + Point<2>(0.005 * i, 0.005 * j), 1.0, 1.0, 0, 0);
        store.stress[p][0][0] = s;
        store.strain[p][0][0] = s / 30e9;
      }
  lme_mpm_test::sort_by_grid_cells(store, grid);
  coupling.update(store);
  std::vector<bool> result;
  for (const Point<2> &centre : {cold_tip, hot_ring})
    for (std::size_t p = 0; p < store.size(); ++p)
      if (store.position[p].distance(centre) < 1e-12)
        result.push_back(store.onset_strain[p] > 0);
  return result;
}
} // namespace

TEST(Eigensoftening, OnsetOnTheNeighbourhoodMeanOrOnTheParticlesOwnStress)
{
  // The paper's onset: the tip at 3 f_t does not start (its neighbourhood's mean is
  // below f_t), the particle at 0.9 f_t among particles at 2 f_t does.
  EXPECT_EQ(onsets_of_hot_spots("neighbourhood mean"), std::vector<bool>({false, true}));
  // The crack band model's onset: each on its own stress.
  EXPECT_EQ(onsets_of_hot_spots("own stress"), std::vector<bool>({true, false}));
}
