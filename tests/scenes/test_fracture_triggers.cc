// Fracture triggers on whole runs: rows only near a trigger change nothing; the stage
// table of a fracture run.
#include <deal.II/base/parameter_handler.h>

#include <gtest/gtest.h>

#include <lme_mpm/base/stage_timer.h>
#include <lme_mpm/fracture/fracture_model.h>
#include <lme_mpm/fracture/neighbourhood.h>

#include "test_helpers.h"

#include <cmath>
#include <random>
#include <thread>

using namespace lme_mpm;

namespace
{
/// Runs @p model over a loading history twice, once with every row and once with rows
/// only around the particles above its trigger, and compares the particles bit for bit.
void check_trigger_changes_nothing(const std::string &model_name, ParameterHandler &prm,
                                   const double peak_stress, unsigned int &skipped_rows,
                                   unsigned int &changed)
{
  const double h = 0.01, E = 30e9;
  FractureContext fc;
  fc.grid_spacing   = h;
  fc.p_wave_modulus = E;
  fc.section        = "test";
  const auto model  = FractureModelRegistry<2>::instance().create(model_name, prm, fc);
  const FractureTrigger trigger = model->trigger(h);
  ASSERT_NE(trigger.field, FractureTrigger::Field::none);

  // A 40 x 40 lattice, two particles per cell, under a broad stress peak that grows
  // from 0.9 @p peak_stress by 0.1 % of it per step: within a neighbourhood the
  // stress varies by about 0.5 % (a little noise makes neighbours differ), so the mean
  // reaches a bound soon after the largest member does, and a trigger set even 1 %
  // too high would be caught.
  ParticleStore<2> full, seeded;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> noise(0.999, 1.001);
  std::vector<double> factor;
  for (unsigned int i = 0; i < 40; ++i)
    for (unsigned int j = 0; j < 40; ++j)
    {
      const Point<2> x(0.0025 + 0.005 * i, 0.0025 + 0.005 * j);
      full.add(x, 1.0, 2.5e-5, 0, 0);
      seeded.add(x, 1.0, 2.5e-5, 0, 0);
      factor.push_back(noise(rng));
    }
  const std::size_t n = full.size();
  // Sorted by the cells of a grid, as the solver's store is.
  BackgroundGrid<2> grid;
  grid.reinit(Point<2>(), {{std::vector<double>(20, h), std::vector<double>(20, h)}});
  for (ParticleStore<2> *P : {&full, &seeded})
  {
    for (std::size_t p = 0; p < n; ++p)
    {
      std::array<unsigned int, 2> ij;
      ASSERT_TRUE(grid.locate(P->position[p], ij));
      P->cell[p] = grid.cell_index(ij);
    }
    P->sort_by_cell(grid.n_cells());
  }
  Neighbourhood<2> nb_full, nb_seeded;
  FractureFields F_full, F_seeded;
  std::vector<std::uint8_t> seeds(n);
  const Point<2> centre(0.1, 0.1);
  for (unsigned int step = 1; step <= 600; ++step)
  {
    for (ParticleStore<2> *P : {&full, &seeded})
      for (std::size_t p = 0; p < n; ++p)
      {
        const double r2 = P->position[p].distance_square(centre);
        const double s =
            peak_stress * (0.9 + 1e-3 * step) * std::exp(-r2 / 0.1) * factor[p];
        P->stress[p]       = SymmetricTensor<2, 2>();
        P->stress[p][0][0] = s;
        P->stress[p][1][1] = 0.2 * s;
        P->strain[p]       = P->stress[p] / E;
      }
    for (auto [P, F] : {std::pair{&full, &F_full}, std::pair{&seeded, &F_seeded}})
    {
      F->max_principal_stress.resize(n);
      F->energy_density.resize(n);
      for (std::size_t p = 0; p < n; ++p)
      {
        const bool alive           = !P->failed[p];
        F->max_principal_stress[p] = alive ? eigenvalues(P->stress[p])[0] : 0.0;
        F->energy_density[p] =
            alive ? 0.5 * (1 - P->damage[p]) * (P->stress[p] * P->strain[p]) : 0.0;
        const double field = trigger.field == FractureTrigger::Field::energy_density
                                 ? F->energy_density[p]
                                 : F->max_principal_stress[p];
        seeds[p]           = (field > trigger.threshold ? Neighbourhood<2>::seed : 0) |
                   (alive ? Neighbourhood<2>::takes_row : 0);
      }
    }
    const double radius = model->epsilon(h);
    nb_full.build(full, grid, radius);
    nb_seeded.build(seeded, grid, radius, {}, &seeds);
    skipped_rows += n - nb_seeded.n_rows();
    model->update(full, nb_full, F_full, 0, n, 0);
    model->update(seeded, nb_seeded, F_seeded, 0, n, 0);
    for (std::size_t p = 0; p < n; ++p)
    {
      ASSERT_EQ(full.damage[p], seeded.damage[p]) << "step " << step << " p " << p;
      ASSERT_EQ(full.failed[p], seeded.failed[p]) << "step " << step << " p " << p;
      ASSERT_EQ(full.onset_strain[p], seeded.onset_strain[p]) << "step " << step;
      ASSERT_EQ(full.dissipated[p], seeded.dissipated[p]) << "step " << step;
    }
  }
  for (std::size_t p = 0; p < n; ++p)
    changed += full.onset_strain[p] > 0 || full.failed[p];
}
} // namespace

namespace
{
/// The check above for @p model with the entries @p entries of "Material N/Fracture";
/// returns the rows left out and the particles the model changed.
std::pair<unsigned int, unsigned int>
trigger_check(const std::string &model,
              const std::vector<std::pair<std::string, std::string>> &entries)
{
  ParameterHandler prm;
  declare_fracture_parameters<2>(prm);
  prm.set("Model", model);
  prm.set("Epsilon factor", "2");
  for (const auto &[entry, value] : entries)
    prm.set(entry, value);
  unsigned int skipped = 0, changed = 0;
  check_trigger_changes_nothing(model, prm, 3e6, skipped, changed);
  return {skipped, changed};
}
} // namespace

TEST(FractureTriggers, EigensofteningWithRowsOnlyNearTheTriggerChangesNothing)
{
  const auto [skipped, changed] = trigger_check(
      "eigensoftening", {{"Tensile strength", "3e6"}, {"Fracture energy", "10"}});
  EXPECT_GT(skipped, 0u);  // rows were left out ...
  EXPECT_GT(changed, 20u); // ... and particles started to soften
}

TEST(FractureTriggers, EigenerosionWithRowsOnlyNearTheTriggerChangesNothing)
{
  // Energy density (3e6)^2 (1 + 0.2^2) / (2 E) = 156 J/m^3 at the peak stress
  // against G_c / eps = 200 J/m^3: failures start at about 1.13 times it.
  const auto [skipped, changed] =
      trigger_check("eigenerosion", {{"Fracture energy", "4"}});
  EXPECT_GT(skipped, 0u);
  EXPECT_GT(changed, 5u);
}

TEST(StageTimer, AFractureRunReportsWhereTheTimeWent)
{
  // 4,715 steps (about 0.15 s): long enough that a stall of the machine outside the
  // step (a page fault, a write held up by another job) cannot outweigh the stages.
  const auto v = lme_mpm_test::run_scene(
      "tension_bar.prm", "stage_timer",
      {"Time/End time=1e-3", "Output/Write particle files=false"});
  double sum = 0;
  for (const std::string stage :
       {"locate_and_sort_particles", "shape_functions_particles_to_grid",
        "rates_predictor", "strains_and_stresses", "fracture", "forces",
        "accelerations_corrector", "grid_to_particles"})
  {
    ASSERT_TRUE(v.count("stage_seconds_" + stage)) << stage;
    EXPECT_GT(v.at("stage_seconds_" + stage), 0.0) << stage;
    sum += v.at("stage_seconds_" + stage);
  }
  // Stages do not overlap: together they fit in the run's wall time.
  EXPECT_LE(sum, v.at("wall_seconds"));
  EXPECT_GT(sum, 0.5 * v.at("wall_seconds"));
}
