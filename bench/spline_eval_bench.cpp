// Evaluation throughput of tensor-product splines: the hot path of slicing, analysis and tessellation.
// Figures and the machine they were measured on are in bench/README.md.
#include <benchmark/benchmark.h>

#include <omp.h>

#include <random>
#include <vector>

#include "bench_volumes.hpp"

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

template <int D>
std::vector<Param<D>> random_params(std::size_t n) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  std::vector<Param<D>> u(n);
  for (auto& x : u)
    for (auto& c : x) c = U(rng);
  return u;
}

constexpr std::size_t kPoints = 1000000;

// Runs evaluate(threads) per iteration and reports points/s; state.range(0) is the thread count (0 = all).
template <class Evaluate>
void measure_points(benchmark::State& state, double points, Evaluate&& evaluate) {
  const int threads = state.range(0) > 0 ? static_cast<int>(state.range(0)) : omp_get_max_threads();
  for (auto _ : state) evaluate(threads);
  state.counters["threads"] = threads;
  state.counters["points/s"] =
      benchmark::Counter(points * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_VolumeValue(benchmark::State& state) {
  const auto s = bench::perturbed_cube(3, 8);
  const auto u = random_params<3>(kPoints);
  std::vector<double> out(kPoints * 3);
  measure_points(state, kPoints, [&](int threads) {
    s.eval_batch(u, out, threads);
    benchmark::DoNotOptimize(out.data());
  });
}
BENCHMARK(BM_VolumeValue)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_VolumeValueFirstDerivs(benchmark::State& state) {
  const auto s = bench::perturbed_cube(3, 8);
  const auto u = random_params<3>(kPoints);
  std::vector<double> out(kPoints * 12);
  measure_points(state, kPoints, [&](int threads) {
    s.eval_derivs_batch(u, 1, out, threads);
    benchmark::DoNotOptimize(out.data());
  });
}
BENCHMARK(BM_VolumeValueFirstDerivs)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

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
  const auto u = random_params<2>(kPoints);
  std::vector<double> out(kPoints * 3);
  measure_points(state, kPoints, [&](int threads) {
    s.eval_batch(u, out, threads);
    benchmark::DoNotOptimize(out.data());
  });
}
BENCHMARK(BM_SurfaceValue)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
