// Certified Jacobian check (Bernstein form of det J + subdivision) on a tricubic volume with 8x8x8 elements.
#include <benchmark/benchmark.h>

#include <omp.h>

#include <cmath>
#include <vector>

#include "bench_volumes.hpp"
#include "trivar/spline/jacobian.hpp"

using namespace trivar;

namespace {

// state.range(0): threads (0 = all).
void run(benchmark::State& state, const SplineVolume& s) {
  const int threads = state.range(0) > 0 ? static_cast<int>(state.range(0)) : omp_get_num_procs();
  omp_set_num_threads(threads);
  JacobianReport<3> rep;
  for (auto _ : state) {
    rep = check_jacobian(s);
    benchmark::DoNotOptimize(rep);
  }
  state.counters["threads"] = threads;
  state.counters["valid"] = rep.valid;
  state.counters["min_lower"] = rep.min_lower_bound;
  state.counters["min_value"] = rep.min_value;
  state.counters["subdivisions"] = rep.subdivisions;
  state.counters["elements/s"] =
      benchmark::Counter(static_cast<double>(rep.elements) * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_JacobianTricubic8(benchmark::State& state) { run(state, bench::perturbed_cube(3, 8)); }
BENCHMARK(BM_JacobianTricubic8)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_JacobianRationalTricubic8(benchmark::State& state) { run(state, bench::perturbed_cube(3, 8, 0.05, true)); }
BENCHMARK(BM_JacobianRationalTricubic8)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
