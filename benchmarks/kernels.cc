// Kernel timings (Google Benchmark): shape-function evaluation, cell sort, stress
// update, neighbourhood build, and a whole time step. Items are particles, so the
// reported rate is particles per second (one thread unless the benchmark says so).
// The machine/ benchmarks measure what one core can do at best: memory bandwidth (a
// triad over arrays far larger than the caches), scalar flops and glibc's
// exp, the limits doc/performance.md compares the LME kernel with.
//
//   cmake -S . -B build -DLME_MPM_BUILD_BENCHMARKS=ON && cmake --build build --target
//   kernels
//   ./build/kernels
#include <deal.II/base/multithread_info.h>

#include <benchmark/benchmark.h>

#include <lme_mpm/base/bisection.h>
#include <lme_mpm/fracture/neighbourhood.h>
#include <lme_mpm/fracture/softening_law.h>
#include <lme_mpm/materials/linear_elastic.h>
#include <lme_mpm/shape_functions/lme_simd.h>
#include <lme_mpm/shape_functions/shape_function.h>
#include <lme_mpm/simulation/run.h>
#include <lme_mpm/simulation/simulation.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>

using namespace lme_mpm;

namespace
{
constexpr double h = 0.01;

/// 2D grid of 250 x 100 cells with 4 particles per cell (100,000 particles).
struct Block
{
  BackgroundGrid<2> grid;
  ParticleStore<2> particles;
  Block()
  {
    grid.reinit(Point<2>(-0.1, -0.1),
                {{std::vector<double>(270, h), std::vector<double>(120, h)}});
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> jitter(-0.1 * h, 0.1 * h);
    for (unsigned int i = 0; i < 500; ++i)
      for (unsigned int j = 0; j < 200; ++j)
        particles.add(
            Point<2>((i + 0.5) * h / 2 + jitter(rng), (j + 0.5) * h / 2 + jitter(rng)),
            1.0, h * h / 4, 0, 0);
  }
};

Block &block()
{
  static Block b;
  return b;
}

/// A graded 2D grid as the drop weight's beam: 1.25 mm columns and rows between 2.5 mm
/// ones (cells at most twice as long as wide), with 2 x 2 particles per cell three
/// cells in from its faces (18,000 particles).
struct GradedBlock
{
  BackgroundGrid<2> grid;
  ParticleStore<2> particles;
  GradedBlock()
  {
    const double H = 0.0025;
    std::array<std::vector<double>, 2> steps;
    for (const auto &[n, s] : {std::pair{16, H}, {64, H / 2}, {16, H}})
      steps[0].insert(steps[0].end(), n, s);
    for (const auto &[n, s] : {std::pair{12, H}, {32, H / 2}, {12, H}})
      steps[1].insert(steps[1].end(), n, s);
    grid.reinit(Point<2>(), steps);
    std::mt19937 rng(6);
    std::uniform_real_distribution<double> jitter(-0.1, 0.1);
    for (unsigned int j = 3; j + 3 < steps[1].size(); ++j)
      for (unsigned int i = 3; i + 3 < steps[0].size(); ++i)
      {
        const double hx = grid.spacing(0, i), hy = grid.spacing(1, j);
        for (const double a : {0.25, 0.75})
          for (const double b : {0.25, 0.75})
            particles.add(Point<2>(grid.coordinates(0)[i] + (a + jitter(rng) / 2) * hx,
                                   grid.coordinates(1)[j] + (b + jitter(rng) / 2) * hy),
                          1.0, hx * hy / 4, 0, 0);
      }
  }
};

GradedBlock &graded_block()
{
  static GradedBlock b;
  return b;
}

std::unique_ptr<ShapeFunction<2>> make(const std::string &type, ParameterHandler &prm,
                                       const std::string &lme_kernel = "auto",
                                       const BackgroundGrid<2> *grid = nullptr)
{
  prm.enter_subsection("Shape functions");
  ShapeFunctionRegistry<2>::instance().declare_all(prm);
  prm.set("LME kernel", lme_kernel);
  ShapeFunctionContext<2> context;
  context.grid = grid ? grid : &block().grid;
  auto sf      = ShapeFunctionRegistry<2>::instance().create(type, prm, context);
  prm.leave_subsection();
  return sf;
}

/// One pass of a family's shape functions over the block (or the graded block).
void shape_function_pass(benchmark::State &state, const std::string &type,
                         const bool warm, const std::string &lme_kernel = "auto",
                         const bool graded = false)
{
  MultithreadInfo::set_thread_limit(1);
  ParameterHandler prm;
  auto sf = make(type, prm, lme_kernel, graded ? &graded_block().grid : nullptr);
  auto &P = graded ? graded_block().particles : block().particles;
  Connectivity<2> conn;
  conn.resize(P.size(), sf->max_nodes_per_particle());
  sf->compute(P, 0, P.size(), conn); // converged multipliers for the warm start
  for (auto _ : state)
  {
    if (!warm)
      std::fill(P.lme_lambda.begin(), P.lme_lambda.end(), Tensor<1, 2>());
    sf->compute(P, 0, P.size(), conn);
    benchmark::DoNotOptimize(conn.N.data());
  }
  state.SetItemsProcessed(state.iterations() * P.size());
}

void cell_sort(benchmark::State &state)
{
  ParticleStore<2> P = block().particles;
  std::mt19937 rng(1);
  for (auto _ : state)
  {
    state.PauseTiming();
    for (auto &c : P.cell) // a shuffled order: the worst case
      c = rng() % block().grid.n_cells();
    state.ResumeTiming();
    P.sort_by_cell(block().grid.n_cells());
  }
  state.SetItemsProcessed(state.iterations() * P.size());
}

void stress_update(benchmark::State &state)
{
  ParticleStore<2> P = block().particles;
  materials::LinearElastic<2> m(1000, 1e9, 0.3, PlaneAssumption::plane_strain);
  for (auto &de : P.strain_increment)
    de[0][0] = 1e-6, de[0][1] = 2e-7;
  for (auto _ : state)
    m.update_stress(P, 0, P.size(), 0);
  state.SetItemsProcessed(state.iterations() * P.size());
}

void neighbourhood(benchmark::State &state)
{
  MultithreadInfo::set_thread_limit(1);
  // The neighbourhood reads the store's order: the particles sorted by their cells.
  ParticleStore<2> P            = block().particles;
  const BackgroundGrid<2> &grid = block().grid;
  std::array<unsigned int, 2> ijk;
  for (std::size_t p = 0; p < P.size(); ++p)
  {
    grid.locate(P.position[p], ijk);
    P.cell[p] = grid.cell_index(ijk);
  }
  P.sort_by_cell(grid.n_cells());
  Neighbourhood<2> nb;
  for (auto _ : state)
    nb.build(P, grid, 2 * h);
  state.SetItemsProcessed(state.iterations() * block().particles.size());
}

/// The LME exponential pass alone (scalar std::exp or the SIMD one) over rows of 24
/// nodes, the 2D support at gamma 1.8: items are nodes.
void lme_exponential_pass(benchmark::State &state, const bool simd)
{
  const auto *kernels = simd ? lme_mpm::shape_functions::lme_simd::avx2_kernels()
                             : &lme_mpm::shape_functions::lme_simd::scalar_kernels();
  if (kernels == nullptr)
  {
    state.SkipWithError("no AVX2 with FMA on this processor");
    return;
  }
  constexpr unsigned int n = 24, rows = 1024;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> offset(-2.7, 2.7);
  std::vector<double> y0(n * rows), y1(n * rows), a(n * rows), N(n);
  for (unsigned int i = 0; i < n * rows; ++i)
    y0[i] = offset(rng), y1[i] = offset(rng),
    a[i] = -1.8 * (y0[i] * y0[i] + y1[i] * y1[i]);
  lme_mpm::shape_functions::lme_simd::Moments2 m;
  for (auto _ : state)
    for (unsigned int r = 0; r < rows; ++r)
    {
      kernels->exponential(&a[r * n], &y0[r * n], &y1[r * n], n, 0.1, -0.2, N.data(), m);
      benchmark::DoNotOptimize(m);
    }
  state.SetItemsProcessed(state.iterations() * n * rows);
}

/// A whole step of the throughput scene (benchmarks/throughput.prm).
void time_step(benchmark::State &state, const std::string &type)
{
  MultithreadInfo::set_thread_limit(state.range(0));
  ParameterHandler prm;
  ParameterCounts counts;
  Simulation<2>::declare_parameters(prm, counts);
  prm.parse_input(std::string(LME_MPM_SOURCE_DIR) + "/benchmarks/throughput.prm");
  apply_overrides(prm, {"Shape functions/Type=" + type, "Output/Verbosity=0"}, false);
  std::ostringstream quiet;
  Simulation<2> sim(prm, counts, quiet);
  sim.step();
  for (auto _ : state)
    sim.step();
  state.SetItemsProcessed(state.iterations() * sim.particles().size());
  MultithreadInfo::set_thread_limit();
}
/// a = b + s c over three arrays of 2^23 doubles (192 MiB): bytes read and written.
void machine_triad(benchmark::State &state)
{
  const std::size_t n = std::size_t(1) << 23;
  std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
  for (auto _ : state)
  {
    const double s = 0.5;
    for (std::size_t i = 0; i < n; ++i)
      a[i] = b[i] + s * c[i];
    benchmark::DoNotOptimize(a.data());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(state.iterations() * 3 * n * sizeof(double));
}

/// Sixteen independent chains of a multiply and an add (the default x86-64 target has no
/// FMA instruction; the compiler may pack pairs into SSE2): items are flops, two per
/// link. The ceiling for arithmetic compiled with the project's flags.
void machine_flops(benchmark::State &state)
{
  double x[16];
  for (unsigned int k = 0; k < 16; ++k)
    x[k] = 1 + 0.1 * k;
  const double a = 0.999999, b = 1e-7;
  const long n = 1 << 19;
  for (auto _ : state)
  {
    for (long i = 0; i < n; ++i)
      for (double &xi : x)
        xi = xi * a + b;
    benchmark::DoNotOptimize(x);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * n * 16 * 2);
}

#if defined(__x86_64__) && defined(__GNUC__)
/// As machine_flops with AVX2 fused multiply-adds, four doubles each, in the SIMD LME
/// passes' instruction set: items are flops, two per lane and link.
__attribute__((target("avx2,fma"))) void machine_fma_avx2(benchmark::State &state)
{
  if (!lme_mpm::shape_functions::lme_simd::avx2_kernels())
  {
    state.SkipWithError("no AVX2 with FMA on this processor");
    return;
  }
  typedef double v4 __attribute__((vector_size(32)));
  v4 x[12];
  for (unsigned int k = 0; k < 12; ++k)
    x[k] = v4{1.0, 1.1, 1.2, 1.3} + 0.01 * k;
  const v4 a = {0.999999, 0.999999, 0.999999, 0.999999}, b = {1e-7, 1e-7, 1e-7, 1e-7};
  const long n = 1 << 18;
  for (auto _ : state)
  {
    for (long i = 0; i < n; ++i)
      for (v4 &xi : x)
        xi = xi * a + b;
    benchmark::DoNotOptimize(x);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * n * 12 * 4 * 2);
}
#endif

/// Eigensoftening's crack opening solve, F(w) = s0 (g(w) - 1) / M + w / h - e = 0, with
/// the built-in linear law and the drop weight's numbers (f_t = 5.4 MPa, G_F = 141 N/m,
/// E = 31 GPa, h = 1.875 mm), strains from the first step of softening to the law's
/// end: the full bisection, or the one that asks the law only near the root (the same
/// ends). Items are solves.
void opening_solve(benchmark::State &state, const bool near_root)
{
  ParameterHandler prm;
  SofteningContext c;
  c.tensile_strength = 5.4e6;
  c.fracture_energy  = 141;
  c.section          = "benchmark";
  const auto law     = SofteningLawRegistry::instance().create("linear", prm, c);
  const double w_c = law->critical_opening(), M = 31e9, s0 = 5.4e6, h = 1.875e-3;
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<double> strains(20000);
  for (double &e : strains)
    e = std::ldexp(unit(rng), -int(20 * unit(rng))) * w_c / h;
  const double slope = (1 / h - s0 * law->max_slope() / M) * (1 - 1e-9);
  for (auto _ : state)
    for (const double e : strains)
    {
      const auto F = [&](const double w)
      { return s0 * (law->traction_ratio(w) - 1) / M + w / h - e; };
      double lo = 0, hi = w_c;
      if (near_root)
        bisect_increasing(lo, hi, 60, F, slope,
                          [&](const double w)
                          {
                            return 64 * std::numeric_limits<double>::epsilon() *
                                   (s0 / M + std::abs(w) / h + std::abs(e));
                          });
      else
        bisect(lo, hi, 60, [&](const double x) { return !(F(x) > 0); });
      benchmark::DoNotOptimize(lo);
      benchmark::DoNotOptimize(hi);
    }
  state.SetItemsProcessed(state.iterations() * strains.size());
}

/// glibc exp over independent arguments (the LME kernel's calls): items are calls.
void machine_exp(benchmark::State &state)
{
  std::vector<double> x(4096);
  for (std::size_t i = 0; i < x.size(); ++i)
    x[i] = -10.0 * i / x.size();
  for (auto _ : state)
  {
    double sum = 0;
    for (const double xi : x)
      sum += std::exp(xi);
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * x.size());
}
} // namespace

BENCHMARK(machine_triad)->Unit(benchmark::kMillisecond);
BENCHMARK(machine_flops)->Unit(benchmark::kMillisecond);
#if defined(__x86_64__) && defined(__GNUC__)
BENCHMARK(machine_fma_avx2)->Unit(benchmark::kMillisecond);
#endif
BENCHMARK(machine_exp)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(lme_exponential_pass, scalar, false)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(lme_exponential_pass, avx2, true)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(shape_function_pass, linear, "linear", true)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(shape_function_pass, ugimp, "ugimp", true)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(shape_function_pass, bspline, "bspline", true)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(shape_function_pass, lme_warm, "lme", true)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(shape_function_pass, lme_cold, "lme", false)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(shape_function_pass, lme_warm_scalar, "lme", true, "scalar")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(shape_function_pass, lme_cold_scalar, "lme", false, "scalar")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(shape_function_pass, lme_warm_graded, "lme", true, "auto", true)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(opening_solve, bisect, false)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(opening_solve, near_root, true)->Unit(benchmark::kMicrosecond);
BENCHMARK(cell_sort)->Unit(benchmark::kMillisecond);
BENCHMARK(stress_update)->Unit(benchmark::kMillisecond);
BENCHMARK(neighbourhood)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(time_step, linear, "linear")
    ->Arg(1)
    ->Arg(2)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(time_step, lme, "lme")
    ->Arg(1)
    ->Arg(2)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
