#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <lme_mpm/shape_functions/lme_simd.h>

#if defined(__x86_64__) && defined(__GNUC__)
#define LME_MPM_HAVE_AVX2_PATH 1
#include <immintrin.h>
#endif

namespace lme_mpm
{
namespace shape_functions
{
namespace lme_simd
{
namespace
{
// One node's weight e at offset (u, v) into the moment sums, in the order of the
// earlier 2D kernels, which the scalar passes reproduce bit for bit.
inline void add_moments(Moments2 &m, const double e, const double u, const double v)
{
  m.Z += e;
  m.r0 += e * u;
  m.j00 += e * u * u;
  m.j01 += e * u * v;
  m.r1 += e * v;
  m.j11 += e * v * v;
}

double scalar_exponential(const double *a, const double *y0, const double *y1,
                          const unsigned int n, const double mu0, const double mu1,
                          double *N, Moments2 &m)
{
  double f_max = -std::numeric_limits<double>::infinity();
  for (unsigned int I = 0; I < n; ++I)
  {
    N[I]  = a[I] + (mu0 * y0[I] + mu1 * y1[I]);
    f_max = std::max(f_max, N[I]);
  }
  m = {0, 0, 0, 0, 0, 0};
  for (unsigned int I = 0; I < n; ++I)
  {
    N[I] = std::exp(N[I] - f_max);
    add_moments(m, N[I], y0[I], y1[I]);
  }
  return f_max;
}

void scalar_polynomial(const double *y0, const double *y1, const unsigned int n,
                       const double s0, const double s1, const double r0, const double r1,
                       double *N, Moments2 &m)
{
  m = {0, 0, 0, 0, 0, 0};
  for (unsigned int I = 0; I < n; ++I)
  {
    const double t = s0 * (y0[I] - r0) + s1 * (y1[I] - r1);
    N[I] *= 1 + t * (1 + t * (0.5 + t * (1. / 6)));
    add_moments(m, N[I], y0[I], y1[I]);
  }
}

#ifdef LME_MPM_HAVE_AVX2_PATH
#define LME_MPM_AVX2 __attribute__((target("avx2,fma")))

// exp(x) for x <= 0 (every argument here is an exponent minus the largest one).
// x = k ln 2 + r with |r| <= ln 2 / 2 and k an integer; exp(r) from its Taylor
// polynomial to degree 13 (remainder below 5e-18), times 2^k built in the exponent
// bits. Below -708 the result is that of -708 (a weight 1e-307 of the largest).
LME_MPM_AVX2 inline __m256d exp_nonpositive(__m256d x)
{
  const __m256d log2e = _mm256_set1_pd(1.4426950408889634);
  // ln 2 split so that k ln2_hi is exact for |k| < 2^11.
  const __m256d ln2_hi = _mm256_set1_pd(6.93145751953125e-1);
  const __m256d ln2_lo = _mm256_set1_pd(1.42860682030941723212e-6);
  x                    = _mm256_max_pd(x, _mm256_set1_pd(-708.0));
  const __m256d k      = _mm256_round_pd(_mm256_mul_pd(x, log2e),
                                         _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
  __m256d r            = _mm256_fnmadd_pd(k, ln2_hi, x);
  r                    = _mm256_fnmadd_pd(k, ln2_lo, r);
  // Estrin's scheme (pairs, then powers r^2, r^4, r^8): a chain of five operations
  // where Horner's has thirteen; the passes' time is this chain's latency.
  const auto c     = [](const double v) LME_MPM_AVX2 { return _mm256_set1_pd(v); };
  const __m256d r2 = _mm256_mul_pd(r, r), r4 = _mm256_mul_pd(r2, r2),
                r8 = _mm256_mul_pd(r4, r4);
  const __m256d q0 = _mm256_fmadd_pd(c(1.0), r, c(1.0));
  const __m256d q1 = _mm256_fmadd_pd(c(1.0 / 6), r, c(1.0 / 2));
  const __m256d q2 = _mm256_fmadd_pd(c(1.0 / 120), r, c(1.0 / 24));
  const __m256d q3 = _mm256_fmadd_pd(c(1.0 / 5040), r, c(1.0 / 720));
  const __m256d q4 = _mm256_fmadd_pd(c(1.0 / 362880), r, c(1.0 / 40320));
  const __m256d q5 = _mm256_fmadd_pd(c(1.0 / 39916800), r, c(1.0 / 3628800));
  const __m256d q6 = _mm256_fmadd_pd(c(1.0 / 6227020800), r, c(1.0 / 479001600));
  const __m256d t0 = _mm256_fmadd_pd(q1, r2, q0), t1 = _mm256_fmadd_pd(q3, r2, q2),
                t2 = _mm256_fmadd_pd(q5, r2, q4);
  const __m256d u0 = _mm256_fmadd_pd(t1, r4, t0), u1 = _mm256_fmadd_pd(q6, r4, t2);
  const __m256d p = _mm256_fmadd_pd(u1, r8, u0);
  // 2^k: k + 1.5 2^52 holds k in its low mantissa bits; shifted by 52 they are the
  // exponent field's offset from 1023.
  const __m256d shifted = _mm256_add_pd(k, _mm256_set1_pd(6755399441055744.0));
  const __m256i bits =
      _mm256_add_epi64(_mm256_slli_epi64(_mm256_castpd_si256(shifted), 52),
                       _mm256_set1_epi64x(1023LL << 52));
  return _mm256_mul_pd(p, _mm256_castsi256_pd(bits));
}

// Lanes [0, remaining) of a group of four.
LME_MPM_AVX2 inline __m256i lanes_below(const unsigned int remaining)
{
  const __m256i index = _mm256_setr_epi64x(0, 1, 2, 3);
  return _mm256_cmpgt_epi64(_mm256_set1_epi64x(remaining), index);
}

LME_MPM_AVX2 inline double horizontal_sum(const __m256d v)
{
  const __m128d s = _mm_add_pd(_mm256_castpd256_pd128(v), _mm256_extractf128_pd(v, 1));
  return _mm_cvtsd_f64(_mm_add_sd(s, _mm_unpackhi_pd(s, s)));
}

// Adds the weights e of four nodes at offsets (u, v) to the six moment sums.
struct Sums
{
  __m256d z, r0, r1, j00, j01, j11;
};

LME_MPM_AVX2 inline void accumulate(Sums &s, const __m256d e, const __m256d u,
                                    const __m256d v)
{
  const __m256d eu = _mm256_mul_pd(e, u), ev = _mm256_mul_pd(e, v);
  s.z   = _mm256_add_pd(s.z, e);
  s.r0  = _mm256_add_pd(s.r0, eu);
  s.r1  = _mm256_add_pd(s.r1, ev);
  s.j00 = _mm256_fmadd_pd(eu, u, s.j00);
  s.j01 = _mm256_fmadd_pd(eu, v, s.j01);
  s.j11 = _mm256_fmadd_pd(ev, v, s.j11);
}

LME_MPM_AVX2 inline void reduce(const Sums &s, Moments2 &m)
{
  m = {horizontal_sum(s.z),   horizontal_sum(s.r0),  horizontal_sum(s.r1),
       horizontal_sum(s.j00), horizontal_sum(s.j01), horizontal_sum(s.j11)};
}

LME_MPM_AVX2 inline Sums zero_sums()
{
  const __m256d z = _mm256_setzero_pd();
  return {z, z, z, z, z, z};
}

LME_MPM_AVX2 double avx2_exponential(const double *a, const double *y0, const double *y1,
                                     const unsigned int n, const double mu0,
                                     const double mu1, double *N, Moments2 &m)
{
  const __m256d m0 = _mm256_set1_pd(mu0), m1 = _mm256_set1_pd(mu1);
  const auto exponent = [&](const unsigned int I) LME_MPM_AVX2
  {
    return _mm256_fmadd_pd(
        m1, _mm256_loadu_pd(y1 + I),
        _mm256_fmadd_pd(m0, _mm256_loadu_pd(y0 + I), _mm256_loadu_pd(a + I)));
  };
  // The largest exponent (lanes past n masked out); the exponents are computed again
  // in the second pass rather than stored, which would stall its loads.
  __m256d f_max = _mm256_set1_pd(-std::numeric_limits<double>::infinity());
  for (unsigned int I = 0; I < n; I += 4)
    f_max =
        _mm256_max_pd(f_max, _mm256_blendv_pd(f_max, exponent(I),
                                              _mm256_castsi256_pd(lanes_below(n - I))));
  __m128d h = _mm_max_pd(_mm256_castpd256_pd128(f_max), _mm256_extractf128_pd(f_max, 1));
  h         = _mm_max_sd(h, _mm_unpackhi_pd(h, h));
  const double largest = _mm_cvtsd_f64(h);
  const __m256d shift  = _mm256_set1_pd(largest);
  Sums s               = zero_sums();
  for (unsigned int I = 0; I < n; I += 4)
  {
    const __m256d e = _mm256_and_pd(exp_nonpositive(_mm256_sub_pd(exponent(I), shift)),
                                    _mm256_castsi256_pd(lanes_below(n - I)));
    _mm256_storeu_pd(N + I, e);
    accumulate(s, e, _mm256_loadu_pd(y0 + I), _mm256_loadu_pd(y1 + I));
  }
  reduce(s, m);
  return largest;
}

LME_MPM_AVX2 void avx2_polynomial(const double *y0, const double *y1,
                                  const unsigned int n, const double s0, const double s1,
                                  const double r0, const double r1, double *N,
                                  Moments2 &m)
{
  const __m256d step0 = _mm256_set1_pd(s0), step1 = _mm256_set1_pd(s1);
  const __m256d mean0 = _mm256_set1_pd(r0), mean1 = _mm256_set1_pd(r1);
  const __m256d one = _mm256_set1_pd(1.0), half = _mm256_set1_pd(0.5),
                sixth = _mm256_set1_pd(1. / 6);
  Sums s              = zero_sums();
  for (unsigned int I = 0; I < n; I += 4)
  {
    const __m256d u = _mm256_loadu_pd(y0 + I), v = _mm256_loadu_pd(y1 + I);
    const __m256d t = _mm256_fmadd_pd(step1, _mm256_sub_pd(v, mean1),
                                      _mm256_mul_pd(step0, _mm256_sub_pd(u, mean0)));
    const __m256d p =
        _mm256_fmadd_pd(t, _mm256_fmadd_pd(t, _mm256_fmadd_pd(t, sixth, half), one), one);
    const __m256d e = _mm256_and_pd(_mm256_mul_pd(_mm256_loadu_pd(N + I), p),
                                    _mm256_castsi256_pd(lanes_below(n - I)));
    _mm256_storeu_pd(N + I, e);
    accumulate(s, e, u, v);
  }
  reduce(s, m);
}
#endif
} // namespace

const Kernels2 &scalar_kernels()
{
  static const Kernels2 k{scalar_exponential, scalar_polynomial, "scalar"};
  return k;
}

const Kernels2 *avx2_kernels()
{
#ifdef LME_MPM_HAVE_AVX2_PATH
  static const Kernels2 k{avx2_exponential, avx2_polynomial, "avx2"};
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"))
    return &k;
#endif
  return nullptr;
}

const Kernels2 &select_kernels(const std::string &choice)
{
  if (choice == "scalar")
    return scalar_kernels();
  if (choice != "auto")
    throw std::invalid_argument("LME kernel '" + choice + "': expected auto or scalar");
  if (const Kernels2 *k = avx2_kernels())
    return *k;
  return scalar_kernels();
}
} // namespace lme_simd
} // namespace shape_functions
} // namespace lme_mpm
