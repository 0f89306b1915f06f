// PointInverter::invert on a curved tricubic volume (4 x 4 x 4 elements): the robust search from scratch
// versus Newton from a nearby guess (the tracing case, where the previous point's parameter is the guess).
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "bench_volumes.hpp"
#include "trivar/spline/point_inversion.hpp"

using namespace trivar;

namespace {

struct Workload {
  SplineVolume s = bench::perturbed_cube(3, 4, 0.15);
  PointInverter<3> inverter{s};
  std::vector<Param<3>> params, guesses;
  std::vector<double> points;
  Workload() {
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    std::normal_distribution<double> N(0.0, 0.01);
    for (int i = 0; i < 1024; ++i) {
      const Param<3> u{U(rng), U(rng), U(rng)};
      params.push_back(u);
      guesses.push_back({u[0] + N(rng), u[1] + N(rng), u[2] + N(rng)});
      double x[3];
      s.eval(u, x);
      points.insert(points.end(), x, x + 3);
    }
  }
};

const Workload& workload() {
  static const Workload w;
  return w;
}

void BM_InvertWithoutGuess(benchmark::State& state) {
  const Workload& w = workload();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(w.inverter.invert(w.points.data() + 3 * i));
    i = (i + 1) % w.params.size();
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_InvertWithoutGuess);

void BM_InvertWithGuess(benchmark::State& state) {
  const Workload& w = workload();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(w.inverter.invert(w.points.data() + 3 * i, w.guesses[i]));
    i = (i + 1) % w.params.size();
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_InvertWithGuess);

void BM_NewtonOnly(benchmark::State& state) {
  const Workload& w = workload();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(w.inverter.newton(w.points.data() + 3 * i, w.guesses[i]));
    i = (i + 1) % w.params.size();
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_NewtonOnly);

}  // namespace

BENCHMARK_MAIN();
