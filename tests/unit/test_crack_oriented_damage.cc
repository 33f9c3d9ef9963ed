// Crack-oriented damage on one material point driven along strain paths, against
// isotropic damage: a closed crack carries its compression, a cracked particle
// carries the stress parallel to its crack, and a biaxial state like the Brazilian
// disc's centre cracks across its tension and keeps its compression.
#include <gtest/gtest.h>

#include <lme_mpm/base/tensor_tools.h>
#include <lme_mpm/fracture/fracture_coupling.h>
#include <lme_mpm/grid/background_grid.h>
#include <lme_mpm/materials/material_set.h>
#include <lme_mpm/particles/damage_form.h>

#include "sorted_particles.h"

#include <cmath>
#include <iostream>
#include <string>
#include <type_traits>

using namespace lme_mpm;

namespace
{
/**
 * One concrete particle (E = 30 GPa, nu = 0.2, f_t = 3 MPa, G_F = 100 N/m, linear
 * softening in a band 5 mm wide; its volume is the band's per unit crack area) whose
 * strain is prescribed: each step sets the strain, lets the material update the
 * stress and the fracture coupling update the damage, as a run's step does.
 */
template <int dim>
class MaterialPoint
{
public:
  static constexpr double E = 30e9, nu = 0.2, h = 0.005, G_F = 100;

  explicit MaterialPoint(const std::string &form)
  {
    ParameterHandler prm;
    MaterialSet<dim>::declare_parameters(prm, 1);
    FractureCoupling<dim>::declare_parameters(prm, 1);
    prm.enter_subsection("Material 1");
    prm.set("Density", "2400");
    prm.enter_subsection("linear elastic");
    prm.set("Young's modulus", "30e9");
    prm.set("Poisson's ratio", "0.2");
    prm.leave_subsection();
    prm.enter_subsection("Fracture");
    prm.set("Model", "eigensoftening");
    prm.set("Tensile strength", "3e6");
    prm.set("Fracture energy", "100");
    prm.set("Band width", "0.005");
    prm.set("Damage form", form);
    prm.leave_subsection();
    prm.leave_subsection();
    materials.parse_parameters(prm, 1, false);
    std::array<std::vector<double>, dim> steps;
    for (auto &s : steps)
      s.assign(20, 0.01);
    Point<dim> lower;
    for (unsigned int d = 0; d < dim; ++d)
      lower[d] = -0.1;
    grid.reinit(lower, steps);
    coupling.parse_parameters(prm, materials, grid, 1);
    // The particle's volume is the band's: h per unit area of its crack.
    store.add(Point<dim>(), 2400 * h, h, 0, 0);
    lme_mpm_test::sort_by_grid_cells(store, grid);
    // lambda and M in plane strain (2D) or 3D.
    lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
    M      = lambda + E / (1 + nu);
  }

  /// Moves the strain to @p target in @p n equal steps.
  void strain_to(const SymmetricTensor<2, dim> &target, const unsigned int n = 2000)
  {
    const SymmetricTensor<2, dim> start = store.strain[0];
    for (unsigned int i = 1; i <= n; ++i)
    {
      const SymmetricTensor<2, dim> next = start + (double(i) / n) * (target - start);
      store.strain_increment[0]          = next - store.strain[0];
      store.strain[0]                    = next;
      materials[0].update_stress(store, 0, 1, 0);
      coupling.update(store);
    }
  }

  SymmetricTensor<2, dim> stress() const { return effective_stress(store, 0); }
  /// The elastic stress of the strain now: what an intact particle carries.
  SymmetricTensor<2, dim> elastic() const
  {
    const auto &e = store.strain[0];
    return lambda * trace(e) * unit_symmetric_tensor<dim>() + (M - lambda) * e;
  }
  /// A uniaxial strain along x.
  static SymmetricTensor<2, dim> stretch_x(const double e)
  {
    SymmetricTensor<2, dim> s;
    s[0][0] = e;
    return s;
  }

  ParticleStore<dim> store;
  double lambda = 0, M = 0;

private:
  MaterialSet<dim> materials;
  BackgroundGrid<dim> grid;
  FractureCoupling<dim> coupling;
};

template <class Dimension>
class CrackOrientedDamage : public ::testing::Test
{
};
using Dimensions =
    ::testing::Types<std::integral_constant<int, 2>, std::integral_constant<int, 3>>;
TYPED_TEST_SUITE(CrackOrientedDamage, Dimensions);
} // namespace

TYPED_TEST(CrackOrientedDamage, AClosedCrackCarriesTheFullElasticCompression)
{
  constexpr int dim = TypeParam::value;
  for (const std::string form : {"crack oriented", "isotropic"})
  {
    MaterialPoint<dim> point(form);
    point.strain_to(MaterialPoint<dim>::stretch_x(2e-4)); // past the 1e-4 of f_t / M
    EXPECT_GT(point.store.damage[0], 0) << form;
    // Open it fully (in steps of 1e-5 through the softening, which ends near 1.3e-2),
    // then close it and push the faces together.
    point.strain_to(MaterialPoint<dim>::stretch_x(2e-2));
    point.strain_to(MaterialPoint<dim>::stretch_x(2e-1));
    EXPECT_EQ(point.store.damage[0], 1.0) << form;
    EXPECT_LT(std::abs(point.stress()[0][0]), 1e-6 * point.elastic()[0][0]) << form;
    // The band dissipated G_F per unit crack area (its volume is h per unit area).
    EXPECT_NEAR(point.store.dissipated[0] / MaterialPoint<dim>::G_F, 1.0, 0.02) << form;
    point.strain_to(MaterialPoint<dim>::stretch_x(-1e-4));
    const double across = point.stress()[0][0], elastic = point.elastic()[0][0];
    std::cout << dim << "D, " << form << ": closed crack carries " << across
              << " Pa across it, an intact particle " << elastic << " Pa" << std::endl;
    ASSERT_LT(elastic, -1e6);
    if (form == "crack oriented")
    {
      EXPECT_NEAR(across / elastic, 1.0, 0.01);
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = i; j < dim; ++j)
          EXPECT_NEAR(point.stress()[i][j], point.elastic()[i][j],
                      1e-9 * std::abs(elastic));
    }
    else // the isotropic damage has lost the compression with the tension
      EXPECT_LT(std::abs(across), 0.01 * std::abs(elastic));
  }
}

TYPED_TEST(CrackOrientedDamage, AnOpenCrackCarriesTheStressParallelToIt)
{
  constexpr int dim = TypeParam::value;
  for (const std::string form : {"crack oriented", "isotropic"})
  {
    MaterialPoint<dim> point(form);
    point.strain_to(MaterialPoint<dim>::stretch_x(2e-1));
    ASSERT_EQ(point.store.damage[0], 1.0);
    // Stretch it along y, in the crack's plane, by 1e-4 (3 MPa in an intact plate).
    SymmetricTensor<2, dim> e = point.store.strain[0];
    e[1][1]                   = 1e-4;
    point.strain_to(e);
    // The crack's faces are free: the particle carries sigma_yy of a plate free
    // across x, (M - lambda^2 / M) eps_yy, and no traction across the crack.
    const double M = point.M, lambda = point.lambda;
    const double expected = (M - lambda * lambda / M) * 1e-4;
    const double parallel = point.stress()[1][1];
    std::cout << dim << "D, " << form << ": an open crack stretched along it carries "
              << parallel << " Pa, a plate free across it " << expected << " Pa"
              << std::endl;
    if (form == "crack oriented")
    {
      EXPECT_NEAR(parallel / expected, 1.0, 0.01);
      EXPECT_LT(std::abs(point.stress()[0][0]), 1e-6 * expected);
    }
    else
      EXPECT_LT(std::abs(parallel), 0.01 * expected);
  }
}

TYPED_TEST(CrackOrientedDamage, TensionWithThreeTimesTheCompressionCracksAcrossTheTension)
{
  // The Brazilian disc's centre: sigma_xx = T, sigma_yy = -3 T (zero strain along z in
  // 3D), loaded until the crack is fully open.
  constexpr int dim = TypeParam::value;
  for (const std::string form : {"crack oriented", "isotropic"})
  {
    MaterialPoint<dim> point(form);
    const double M = point.M, lambda = point.lambda;
    // lambda a + M b = -3 (M a + lambda b).
    const double a = 1, b = -(3 * M + lambda) / (M + 3 * lambda);
    SymmetricTensor<2, dim> direction;
    direction[0][0] = a, direction[1][1] = b;
    point.strain_to(1e-4 * direction);
    EXPECT_EQ(point.store.damage[0], 0.0) << form; // sigma_xx = 2.5 MPa < f_t
    point.strain_to(2e-2 * direction); // 100 um over the band: past w_c = 67 um
    ASSERT_EQ(point.store.damage[0], 1.0) << form;
    const double compression = point.stress()[1][1];
    const double released    = (M - lambda * lambda / M) * point.store.strain[0][1][1];
    std::cout << dim << "D, " << form << ": sigma_yy " << compression
              << " Pa with the crack open, " << released
              << " Pa in a plate free across x, " << point.elastic()[1][1] << " Pa intact"
              << std::endl;
    ASSERT_LT(released, -1e7);
    if (form == "crack oriented")
    {
      // The crack is normal to x, and the compression along y is carried in full.
      EXPECT_GT(std::abs(point.store.crack_normal[0][0]), 0.999);
      EXPECT_NEAR(compression / released, 1.0, 0.01);
      EXPECT_LT(std::abs(point.stress()[0][0]), 1e-6 * std::abs(released));
    }
    else // the isotropic damage loses it with the tension
      EXPECT_LT(std::abs(compression), 0.01 * std::abs(released));
  }
}
