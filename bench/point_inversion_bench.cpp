// PointInverter::invert on a curved tricubic volume (4 x 4 x 4 elements): the robust search from scratch
// versus Newton from a nearby guess (the tracing case, where the previous point's parameter is the guess).
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "trivar/spline/point_inversion.hpp"

using namespace trivar;

namespace {

// Greville points of uniform cubic knots under a smooth near-identity deformation (positive Jacobian).
SplineVolume curved_tricubic() {
  std::array<KnotVector, 3> kv;
  for (auto& k : kv) k = KnotVector::open_uniform(3, 4);
  const auto g = kv[0].greville();
  const double pi = std::numbers::pi;
  std::vector<double> pts;
  for (double c : g)
    for (double b : g)
      for (double a : g) {
        pts.push_back(a + 0.15 * std::sin(pi * b));
        pts.push_back(b + 0.15 * std::sin(pi * c));
        pts.push_back(c + 0.1 * std::sin(pi * a));
      }
  return SplineVolume::from_cartesian(kv, 3, pts);
}

struct Workload {
  SplineVolume s = curved_tricubic();
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
