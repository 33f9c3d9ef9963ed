#ifndef LME_MPM_SHAPE_FUNCTIONS_LME_SIMD_H
#define LME_MPM_SHAPE_FUNCTIONS_LME_SIMD_H

// The two passes over a particle's nodes that dominate a 2D local max-ent evaluation,
// in a portable scalar form and, where the processor has them, in AVX2 with FMA. The
// instruction set is chosen when the program runs, so one build runs on any x86-64.
// The arrays are the nodes' scaled offsets y_I in structure-of-arrays form (y0, y1).
// Every array has room for n rounded up to a multiple of four, and its entries past n
// are finite: the SIMD passes read and write whole groups of four (writing 0 past n).

#include <string>

namespace lme_mpm
{
namespace shape_functions
{
namespace lme_simd
{
/// Raw moments of weights e_I: Z = sum e_I, r = sum e_I y_I and the upper triangle of
/// sum e_I y_I y_I^T.
struct Moments2
{
  double Z, r0, r1, j00, j01, j11;
};

/// e_I = exp(a_I + mu . y_I - f_max) into @p N for I < n, with f_max the largest
/// exponent (returned), and their raw moments.
using ExponentialPass = double (*)(const double *a, const double *y0, const double *y1,
                                   unsigned int n, double mu0, double mu1, double *N,
                                   Moments2 &m);

/// N_I *= 1 + t (1 + t (1/2 + t / 6)) with t = s . (y_I - r), the cubic Taylor
/// polynomial of exp(t), and the raw moments of the result.
using PolynomialPass = void (*)(const double *y0, const double *y1, unsigned int n,
                                double s0, double s1, double r0, double r1, double *N,
                                Moments2 &m);

/// One implementation of both passes.
struct Kernels2
{
  ExponentialPass exponential;
  PolynomialPass polynomial;
  const char *name; ///< "scalar" or "avx2"
};

/// The scalar passes: std::exp and the sums in node order, the arithmetic of the
/// earlier 2D kernels (before the SIMD passes) bit for bit.
const Kernels2 &scalar_kernels();

/// The AVX2/FMA passes: four nodes per instruction, an exponential of its own (a
/// degree-13 Taylor polynomial after reduction by powers of two, within 2 ulp of
/// std::exp) and four partial sums per moment. Differs from scalar_kernels() in the
/// last bits. nullptr where the processor lacks AVX2 or FMA.
const Kernels2 *avx2_kernels();

/// @p choice "auto" (the fastest the processor runs) or "scalar".
const Kernels2 &select_kernels(const std::string &choice);
} // namespace lme_simd
} // namespace shape_functions
} // namespace lme_mpm

#endif
