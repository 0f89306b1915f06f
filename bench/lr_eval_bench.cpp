// Random-point evaluation of LR volumes: the tricubic benchmark volume with 8^3 elements converted to an LR
// spline, and the same after two levels of FULLSPAN refinement along the diagonal; 10^6 uniformly random
// parameters. Arg(1): one thread, Arg(0): all. Figures are in bench/README.md.
#include <benchmark/benchmark.h>

#include <omp.h>

#include <random>
#include <vector>

#include "bench_volumes.hpp"
#include "trivar/lr/refinement.hpp"
#include "trivar/lr/selection.hpp"

using namespace trivar;

namespace {

constexpr std::size_t kPoints = 1000000;

LRSpline<3> volume(int levels) {
  LRSpline<3> lr(bench::perturbed_cube(3, 8));
  for (int l = 0; l < levels; ++l) {
    const auto ids = elements_on_segment(lr, Param<3>{0, 0, 0}, Param<3>{1, 1, 1});
    refine_elements(lr, std::span<const int>(ids), RefineOptions{});
  }
  return lr;
}

template <class Evaluate>
void measure_points(benchmark::State& state, Evaluate&& evaluate) {
  const int threads = state.range(0) > 0 ? static_cast<int>(state.range(0)) : omp_get_max_threads();
  for (auto _ : state) evaluate(threads);
  state.counters["threads"] = threads;
  state.counters["points/s"] =
      benchmark::Counter(static_cast<double>(kPoints) * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void value(benchmark::State& state, int levels) {
  const auto lr = volume(levels);
  const auto u = bench::random_params<3>(kPoints);
  std::vector<double> out(kPoints * 3);
  lr.eval(u[0], out.data());  // builds the evaluation data outside the timing
  measure_points(state, [&](int threads) {
    lr.eval_many(u, out, threads);
    benchmark::DoNotOptimize(out.data());
  });
  state.counters["elements"] = lr.num_elements();
}

void first_derivatives(benchmark::State& state, int levels) {
  const auto lr = volume(levels);
  const auto u = bench::random_params<3>(kPoints);
  std::vector<double> out(kPoints * 12);
  lr.eval(u[0], out.data());
  measure_points(state, [&](int threads) {
    lr.eval_first_derivatives_many(u, out, threads);
    benchmark::DoNotOptimize(out.data());
  });
}

void BM_LRVolumeValue(benchmark::State& state) { value(state, 0); }
BENCHMARK(BM_LRVolumeValue)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_LRVolumeFirstDerivs(benchmark::State& state) { first_derivatives(state, 0); }
BENCHMARK(BM_LRVolumeFirstDerivs)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_LRVolumeValueRefined2(benchmark::State& state) { value(state, 2); }
BENCHMARK(BM_LRVolumeValueRefined2)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
