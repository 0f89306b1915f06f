// Scattered-data approximation of terrain: N random points of rolling hills with a crater whose rim is a sharp
// ridge (the local detail), fitted to 0.5 % of the height range with one thread. The LR fit runs to the tolerance;
// the MBA fit (least squares on the start spline, then MBA passes) likewise; the uniform tensor fit runs a fixed number of levels (the full uniform run to the tolerance needs about a million
// coefficients and minutes: its figures from `trivar fit --uniform` are in bench/README.md). Counters: coefficients,
// elements, refinement levels, points outside the tolerance, largest error. Figures are in bench/README.md.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "trivar/fit/lr_approximation.hpp"

using namespace trivar;

namespace {

double terrain(double x, double y) {
  double z = 0.3 * std::exp(-((x - 0.2) * (x - 0.2) + (y - 0.3) * (y - 0.3)) / 0.08) +
             0.2 * std::exp(-((x - 0.8) * (x - 0.8) + (y - 0.7) * (y - 0.7)) / 0.05) + 0.1 * x;
  const double r = std::hypot(x - 0.55, y - 0.45), R = 0.08;
  if (r < R) z += -0.25 * (1 - (r / R) * (r / R)) + 0.1 * (r / R) * (r / R) * (r / R);
  else z += 0.1 * std::exp(-(r - R) / 0.015);
  return z;
}

const ScatteredData<2>& points(std::size_t n) {
  static std::size_t cached_n = 0;
  static ScatteredData<2> d;
  if (cached_n != n) {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    d.dim = 1;
    d.params.resize(n);
    d.values.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      d.params[i] = {u(rng), u(rng)};
      d.values[i] = terrain(d.params[i][0], d.params[i][1]);
    }
    cached_n = n;
  }
  return d;
}

void fit(benchmark::State& state, bool uniform, int levels, FitMethod method = FitMethod::least_squares) {
  const ScatteredData<2>& d = points(static_cast<std::size_t>(state.range(0)));
  double lo = d.values[0], hi = lo;
  for (double v : d.values) lo = std::min(lo, v), hi = std::max(hi, v);
  ApproximationOptions o;
  o.tolerance = 0.005 * (hi - lo);
  o.uniform = uniform;
  o.method = method;
  o.max_levels = levels;
  o.threads = 1;
  for (auto _ : state) {
    const Approximation<2> a = approximate(d, o);
    state.counters["coefficients"] = a.spline.num_basis();
    state.counters["elements"] = a.spline.num_elements();
    state.counters["levels"] = static_cast<double>(a.iterations.size() - 1);
    state.counters["outside"] = static_cast<double>(a.iterations.back().outside);
    state.counters["max_error_over_tol"] = a.iterations.back().max_error / o.tolerance;
  }
}

void BM_FitTerrainLR(benchmark::State& state) { fit(state, false, 12); }
void BM_FitTerrainMBA(benchmark::State& state) { fit(state, false, 16, FitMethod::mba); }
void BM_FitTerrainUniform6Levels(benchmark::State& state) { fit(state, true, 6); }
void BM_FitTerrainUniformMBA6Levels(benchmark::State& state) { fit(state, true, 6, FitMethod::mba); }

}  // namespace

BENCHMARK(BM_FitTerrainLR)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_FitTerrainMBA)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_FitTerrainUniform6Levels)->Arg(1000000)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_FitTerrainUniformMBA6Levels)->Arg(1000000)->Unit(benchmark::kMillisecond)->Iterations(1);

BENCHMARK_MAIN();
