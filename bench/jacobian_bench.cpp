// Certified Jacobian check (Bernstein form of det J + subdivision) on a tricubic volume with 8x8x8 elements.
#include <benchmark/benchmark.h>

#include <omp.h>

#include <cmath>
#include <vector>

#include "trivar/spline/jacobian.hpp"

using namespace trivar;

namespace {

// A smoothly perturbed unit cube (valid: det J in about [0.8, 1.2]), 11^3 control points.
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

// The same volume made rational (interior weights varied), so the homogeneous 4x4 determinant is measured.
SplineVolume rational_tricubic_volume() {
  const SplineVolume s = tricubic_volume();
  std::vector<double> pts(static_cast<std::size_t>(s.num_coefs()) * 3), w(s.num_coefs());
  for (int l = 0; l < s.num_coefs(); ++l) {
    s.control_point(l, pts.data() + 3 * l);
    w[l] = 1.0 + 0.2 * std::sin(l * 0.37);
  }
  return SplineVolume::from_cartesian(s.knot_vectors(), 3, pts, w);
}

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

void BM_JacobianTricubic8(benchmark::State& state) { run(state, tricubic_volume()); }
BENCHMARK(BM_JacobianTricubic8)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_JacobianRationalTricubic8(benchmark::State& state) { run(state, rational_tricubic_volume()); }
BENCHMARK(BM_JacobianRationalTricubic8)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
