// Evaluation throughput of tensor-product splines: the hot path of slicing, analysis and tessellation.
// Figures and the machine they were measured on are in bench/README.md.
#include <benchmark/benchmark.h>

#include <omp.h>

#include <random>
#include <vector>

#include "trivar/spline/tensor_spline.hpp"

using namespace trivar;

namespace {

// Tricubic volume, 8x8x8 elements (11^3 control points), a smoothly perturbed unit cube in 3-space.
SplineVolume tricubic_volume() {
  std::array<KnotVector, 3> kv;
  for (auto& k : kv) k = KnotVector::open_uniform(3, 8);
  const int n = kv[0].size();
  const auto g = kv[0].greville();
  std::vector<double> pts;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double x = g[i], y = g[j], z = g[k];
        pts.insert(pts.end(), {x + 0.05 * std::sin(3 * y), y + 0.05 * std::sin(3 * z), z + 0.05 * std::sin(3 * x)});
      }
  return SplineVolume::from_cartesian(kv, 3, pts);
}

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

// state.range(0): threads (0 = all).
void BM_VolumeValue(benchmark::State& state) {
  const auto s = tricubic_volume();
  const auto u = random_params<3>(kPoints);
  std::vector<double> out(kPoints * 3);
  const int threads = state.range(0) > 0 ? static_cast<int>(state.range(0)) : omp_get_max_threads();
  for (auto _ : state) {
    s.eval_batch(u, out, threads);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["threads"] = threads;
  state.counters["points/s"] = benchmark::Counter(static_cast<double>(kPoints) * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_VolumeValue)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_VolumeValueFirstDerivs(benchmark::State& state) {
  const auto s = tricubic_volume();
  const auto u = random_params<3>(kPoints);
  std::vector<double> out(kPoints * 12);
  const int threads = state.range(0) > 0 ? static_cast<int>(state.range(0)) : omp_get_max_threads();
  for (auto _ : state) {
    s.eval_derivs_batch(u, 1, out, threads);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["threads"] = threads;
  state.counters["points/s"] = benchmark::Counter(static_cast<double>(kPoints) * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_VolumeValueFirstDerivs)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_VolumeGrid100(benchmark::State& state) {
  const auto s = tricubic_volume();
  std::array<std::vector<double>, 3> g;
  for (auto& v : g)
    for (int i = 0; i < 100; ++i) v.push_back(i / 99.0);
  std::vector<double> out(100 * 100 * 100 * 3);
  const int threads = state.range(0) > 0 ? static_cast<int>(state.range(0)) : omp_get_max_threads();
  for (auto _ : state) {
    s.eval_grid(g, out, threads);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["threads"] = threads;
  state.counters["points/s"] = benchmark::Counter(1e6 * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_VolumeGrid100)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_SurfaceValue(benchmark::State& state) {
  const auto s = bicubic_surface();
  const auto u = random_params<2>(kPoints);
  std::vector<double> out(kPoints * 3);
  const int threads = state.range(0) > 0 ? static_cast<int>(state.range(0)) : omp_get_max_threads();
  for (auto _ : state) {
    s.eval_batch(u, out, threads);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["threads"] = threads;
  state.counters["points/s"] = benchmark::Counter(static_cast<double>(kPoints) * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SurfaceValue)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
