// The 2D passes of the local max-ent evaluation: the SIMD ones against the scalar ones
// (the earlier 2D arithmetic bit for bit), and the SIMD exponential's accuracy.

#include <lme_mpm/shape_functions/lme_simd.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

using namespace lme_mpm::shape_functions::lme_simd;

namespace
{
// Offsets and fixed exponents of n nodes around a point, in arrays with room for n
// rounded up to four (as the LME set-up sizes them), their tails finite.
struct Nodes
{
  std::vector<double> a, y0, y1;
  explicit Nodes(const unsigned int n, std::mt19937 &rng)
      : a((n + 3) / 4 * 4, 7.0), y0(a.size(), -3.0), y1(a.size(), 5.0)
  {
    std::uniform_real_distribution<double> offset(-2.7, 2.7);
    for (unsigned int I = 0; I < n; ++I)
    {
      y0[I] = offset(rng), y1[I] = offset(rng);
      a[I] = -1.8 * (y0[I] * y0[I] + y1[I] * y1[I]);
    }
  }
};

void expect_close(const Moments2 &m, const Moments2 &ref, const double tol)
{
  EXPECT_NEAR(m.Z, ref.Z, tol * std::abs(ref.Z));
  const double scale = ref.Z * 8; // |y| <= 2.7 sqrt(2): moments up to 8 Z
  EXPECT_NEAR(m.r0, ref.r0, tol * scale);
  EXPECT_NEAR(m.r1, ref.r1, tol * scale);
  EXPECT_NEAR(m.j00, ref.j00, tol * scale);
  EXPECT_NEAR(m.j01, ref.j01, tol * scale);
  EXPECT_NEAR(m.j11, ref.j11, tol * scale);
}
} // namespace

TEST(LmeSimd, SelectionNamesItsKernels)
{
  EXPECT_STREQ(select_kernels("scalar").name, "scalar");
  const Kernels2 &chosen = select_kernels("auto");
  EXPECT_STREQ(chosen.name, avx2_kernels() ? "avx2" : "scalar");
  EXPECT_THROW(select_kernels("sse9"), std::invalid_argument);
}

TEST(LmeSimd, Avx2PassesAgreeWithScalarOnesForEveryCount)
{
  const Kernels2 *simd = avx2_kernels();
  if (!simd)
    GTEST_SKIP() << "the processor has no AVX2 with FMA";
  const Kernels2 &scalar = scalar_kernels();
  std::mt19937 rng(42);
  // Every count modulo four, up to a 3D-sized row, with multipliers of a warm start and
  // of the far boundary.
  for (unsigned int n = 1; n <= 40; ++n)
    for (const double mu : {0.0, 0.37, -4.0, 25.0})
    {
      const Nodes nodes(n, rng);
      std::vector<double> N_s(nodes.a.size(), -1.0), N_v(nodes.a.size(), -1.0);
      Moments2 m_s, m_v;
      const double f_s =
          scalar.exponential(nodes.a.data(), nodes.y0.data(), nodes.y1.data(), n, mu,
                             -0.5 * mu, N_s.data(), m_s);
      const double f_v =
          simd->exponential(nodes.a.data(), nodes.y0.data(), nodes.y1.data(), n, mu,
                            -0.5 * mu, N_v.data(), m_v);
      // The largest exponent: the same sums, perhaps contracted to one multiply-add.
      EXPECT_NEAR(f_v, f_s, 1e-14 * (1 + std::abs(f_s))) << n << " nodes, mu " << mu;
      for (unsigned int I = 0; I < n; ++I)
        EXPECT_NEAR(N_v[I], N_s[I], 1e-13 * N_s[I] + 1e-300) << I << " of " << n;
      for (unsigned int I = n; I < N_v.size(); ++I)
        EXPECT_EQ(N_v[I], 0.0) << "past n: " << I << " of " << n;
      expect_close(m_v, m_s, 1e-13);

      // The polynomial pass from the weights just found.
      const double s0 = 1e-3, s1 = -2e-3, r0 = m_s.r0 / m_s.Z, r1 = m_s.r1 / m_s.Z;
      scalar.polynomial(nodes.y0.data(), nodes.y1.data(), n, s0, s1, r0, r1, N_s.data(),
                        m_s);
      simd->polynomial(nodes.y0.data(), nodes.y1.data(), n, s0, s1, r0, r1, N_v.data(),
                       m_v);
      for (unsigned int I = 0; I < n; ++I)
        EXPECT_NEAR(N_v[I], N_s[I], 1e-13 * N_s[I] + 1e-300);
      expect_close(m_v, m_s, 1e-13);
    }
}

TEST(LmeSimd, Avx2ExponentialIsWithinTwoUlpOfStdExp)
{
  const Kernels2 *simd = avx2_kernels();
  if (!simd)
    GTEST_SKIP() << "the processor has no AVX2 with FMA";
  // One node per pass (a_0 = x, y = 0): N_0 = exp(x - x) = 1 tells nothing, so two
  // nodes, the first at exponent 0: N_1 = exp(x).
  double worst = 0;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> exponent(-700.0, 0.0);
  for (unsigned int k = 0; k < 200000; ++k)
  {
    const double x    = k < 1000 ? -1e-3 * k : exponent(rng);
    const double a[4] = {0.0, x, 0.0, 0.0}, y[4] = {0, 0, 0, 0};
    double N[4];
    Moments2 m;
    simd->exponential(a, y, y, 2, 0.0, 0.0, N, m);
    const double exact = std::exp(x);
    const double ulp   = std::nextafter(exact, 1e300) - exact;
    worst              = std::max(worst, std::abs(N[1] - exact) / ulp);
    EXPECT_EQ(N[0], 1.0);
  }
  EXPECT_LE(worst, 2.0);
  std::cout << "largest error of the AVX2 exponential on [-700, 0]: " << worst
            << " ulp\n";
}
