// Evaluation throughput of tensor-product splines: the hot path of slicing, analysis and tessellation.
// Figures and the machine they were measured on are in bench/README.md.
#include <benchmark/benchmark.h>

#include <omp.h>

#include <random>
#include <vector>

#include "bench_volumes.hpp"
#include "textbook_eval.hpp"
#include "trivar/spline/simd_level.hpp"

using namespace trivar;

namespace {

SplineSurface bicubic_surface() {
  std::array<KnotVector, 2> kv{KnotVector::open_uniform(3, 20), KnotVector::open_uniform(3, 20)};
  const int n = kv[0].size();
  const auto g = kv[0].greville();
  std::vector<double> pts;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) pts.insert(pts.end(), {g[i], g[j], 0.2 * std::sin(4 * g[i]) * std::cos(3 * g[j])});
  return SplineSurface::from_cartesian(kv, 3, pts);
}

constexpr std::size_t kPoints = 1000000;

// The volume with the kernels of the instruction set state.range(1) (0 generic, 1 AVX2, 2 AVX-512): splines
// choose their kernels when constructed. False (benchmark skipped) when the CPU lacks the level.
bool volume_at_level(benchmark::State& state, SplineVolume& s) {
  const auto level = static_cast<SimdLevel>(state.range(1));
  if (level > supported_simd_level()) {
    state.SkipWithError("instruction set not supported by this CPU");
    return false;
  }
  limit_simd_level(level);
  s = bench::perturbed_cube(3, 8);
  limit_simd_level(supported_simd_level());
  state.SetLabel(simd_level_name(level));
  return true;
}

// Runs evaluate(threads) per iteration and reports points/s; state.range(0) is the thread count (0 = all).
template <class Evaluate>
void measure_points(benchmark::State& state, double points, Evaluate&& evaluate) {
  const int threads = state.range(0) > 0 ? static_cast<int>(state.range(0)) : omp_get_max_threads();
  for (auto _ : state) evaluate(threads);
  state.counters["threads"] = threads;
  state.counters["points/s"] =
      benchmark::Counter(points * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

// Args: threads, instruction set (0 generic, 1 AVX2, 2 AVX-512).
void BM_VolumeValue(benchmark::State& state) {
  SplineVolume s;
  if (!volume_at_level(state, s)) return;
  const auto u = bench::random_params<3>(kPoints);
  std::vector<double> out(kPoints * 3);
  measure_points(state, kPoints, [&](int threads) {
    s.eval_batch(u, out, threads);
    benchmark::DoNotOptimize(out.data());
  });
}
BENCHMARK(BM_VolumeValue)->ArgsProduct({{1, 0}, {0, 1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime();

// The textbook loop of textbook_eval.hpp on the same volume and points, 1 thread: the yardstick of the ratio.
void BM_VolumeValueTextbook(benchmark::State& state) {
  const auto s = bench::perturbed_cube(3, 8);
  std::array<std::vector<double>, 3> t;
  for (int k = 0; k < 3; ++k) t[k] = s.knots(k).knots();
  const bench::TextbookVolume tb(3, t, {s.coefs().begin(), s.coefs().end()});
  const auto u = bench::random_params<3>(kPoints);
  std::vector<double> out(kPoints * 3);
  measure_points(state, kPoints, [&](int) {
    for (std::size_t i = 0; i < kPoints; ++i) tb.eval(u[i], out.data() + 3 * i);
    benchmark::DoNotOptimize(out.data());
  });
}
BENCHMARK(BM_VolumeValueTextbook)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_VolumeValueFirstDerivs(benchmark::State& state) {
  SplineVolume s;
  if (!volume_at_level(state, s)) return;
  const auto u = bench::random_params<3>(kPoints);
  std::vector<double> out(kPoints * 12);
  measure_points(state, kPoints, [&](int threads) {
    s.eval_derivs_batch(u, 1, out, threads);
    benchmark::DoNotOptimize(out.data());
  });
}
BENCHMARK(BM_VolumeValueFirstDerivs)->ArgsProduct({{1, 0}, {0, 1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_VolumeGrid100(benchmark::State& state) {
  const auto s = bench::perturbed_cube(3, 8);
  std::array<std::vector<double>, 3> g;
  for (auto& v : g)
    for (int i = 0; i < 100; ++i) v.push_back(i / 99.0);
  std::vector<double> out(100 * 100 * 100 * 3);
  measure_points(state, 1e6, [&](int threads) {
    s.eval_grid(g, out, threads);
    benchmark::DoNotOptimize(out.data());
  });
}
BENCHMARK(BM_VolumeGrid100)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_SurfaceValue(benchmark::State& state) {
  const auto s = bicubic_surface();
  const auto u = bench::random_params<2>(kPoints);
  std::vector<double> out(kPoints * 3);
  measure_points(state, kPoints, [&](int threads) {
    s.eval_batch(u, out, threads);
    benchmark::DoNotOptimize(out.data());
  });
}
BENCHMARK(BM_SurfaceValue)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
