// LR refinement benchmarks of the issue: cubic, open uniform knots on [0,1]^d, n elements per direction; at each
// level refine every element (FULLSPAN) or B-spline (STRUCTURED) whose open interior meets the diagonal segment
// (0,..,0)-(1,..,1). Each benchmark runs all levels once and prints one line per level:
//   level L: refined K, basis N, elements E, meshrects M, seconds T
// (T covers the selection and the refinement). Figures are in bench/README.md.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdio>
#include <vector>

#include "lr_diagonal.hpp"

using namespace trivar;
using trivar::bench::refine_diagonal;
using trivar::bench::unit_lr;

namespace {

template <int D>
void run_levels(benchmark::State& state, int n, int levels, Strategy strategy) {
  for (auto _ : state) {
    auto lr = unit_lr<D>(n);
    double total = 0.0;
    std::printf("%dD n=%d %s\n", D, n, to_string(strategy));
    for (int level = 1; level <= levels; ++level) {
      const auto t0 = std::chrono::steady_clock::now();
      const std::size_t refined = refine_diagonal(lr, strategy);
      const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      total += secs;
      std::printf("level %d: refined %zu, basis %d, elements %d, meshrects %zu, seconds %.4f\n", level, refined,
                  lr.num_basis(), lr.num_elements(), lr.mesh().size(), secs);
    }
    std::printf("total seconds %.4f\n", total);
    state.counters["basis"] = lr.num_basis();
    state.counters["elements"] = lr.num_elements();
  }
}

void BM_FullSpan2D_n16_5levels(benchmark::State& state) { run_levels<2>(state, 16, 5, Strategy::fullspan); }
BENCHMARK(BM_FullSpan2D_n16_5levels)->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_FullSpan3D_n16_5levels(benchmark::State& state) { run_levels<3>(state, 16, 5, Strategy::fullspan); }
BENCHMARK(BM_FullSpan3D_n16_5levels)->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Structured3D_n8_3levels(benchmark::State& state) { run_levels<3>(state, 8, 3, Strategy::structured); }
BENCHMARK(BM_Structured3D_n8_3levels)->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
