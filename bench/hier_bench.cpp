// Hierarchical (THB) splines: refining ten levels at one corner of the tricubic benchmark volume (8^3 level-0
// elements; geometry coefficients carried along), in two variants: one cell per level (G+Smo's slow case) and
// the (p+1)^3 cells at the corner per level (new functions on every level); and random-point evaluation of the
// tricubic THB volume after three corner levels, 10^6 uniformly random parameters (Arg(1): one thread, Arg(0):
// all). Figures are in bench/README.md.
#include <benchmark/benchmark.h>

#include <omp.h>

#include <random>
#include <vector>

#include "bench_volumes.hpp"
#include "trivar/hier/hierarchical_spline.hpp"

using namespace trivar;

namespace {

constexpr std::size_t kPoints = 1000000;

// The leaf cells of the finest level inside [0, width cells of that level)^3 at the corner u = 0, refined.
void refine_corner(HierarchicalSpline<3>& h, int width) {
  const int level = h.space().num_levels() - 1;
  std::vector<Ints<3>> cells;
  for (int k = 0; k < width; ++k)
    for (int j = 0; j < width; ++j)
      for (int i = 0; i < width; ++i)
        if (h.space().find_leaf(level, {i, j, k}) >= 0) cells.push_back({i, j, k});
  h.refine_cells(level, cells);
}

void corner_levels(benchmark::State& state) {
  const int width = static_cast<int>(state.range(0));
  const HierarchicalSpline<3> start(bench::perturbed_cube(3, 8));
  int functions = 0, elements = 0;
  for (auto _ : state) {
    HierarchicalSpline<3> h = start;
    for (int l = 0; l < 10; ++l) refine_corner(h, width);
    functions = h.space().num_basis();
    elements = h.space().num_elements();
    benchmark::DoNotOptimize(h.coefs().data());
  }
  state.counters["functions"] = functions;
  state.counters["elements"] = elements;
}

HierarchicalSpline<3> refined_volume() {
  HierarchicalSpline<3> h(bench::perturbed_cube(3, 8));
  for (int l = 0; l < 3; ++l) refine_corner(h, 4 << l);
  return h;
}

template <class Evaluate>
void measure_points(benchmark::State& state, const HierarchicalSpline<3>& h, Evaluate&& evaluate) {
  const int threads = state.range(0) > 0 ? static_cast<int>(state.range(0)) : omp_get_max_threads();
  h.evaluator();  // built outside the timing
  for (auto _ : state) evaluate(threads);
  state.counters["threads"] = threads;
  state.counters["elements"] = h.space().num_elements();
  state.counters["points/s"] =
      benchmark::Counter(static_cast<double>(kPoints) * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void value(benchmark::State& state) {
  const auto h = refined_volume();
  const auto u = bench::random_params<3>(kPoints);
  std::vector<double> out(kPoints * 3);
  measure_points(state, h, [&](int threads) {
    h.eval_many(u, out, threads);
    benchmark::DoNotOptimize(out.data());
  });
}

void first_derivatives(benchmark::State& state) {
  const auto h = refined_volume();
  const auto u = bench::random_params<3>(kPoints);
  std::vector<double> out(kPoints * 12);
  measure_points(state, h, [&](int threads) {
    const auto& ev = h.evaluator();
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t>(kPoints); ++i)
      ev.eval_first_derivatives(h.space(), u[static_cast<std::size_t>(i)], out.data() + i * 12);
    benchmark::DoNotOptimize(out.data());
  });
}

void build_evaluator(benchmark::State& state) {
  const auto h = refined_volume();
  for (auto _ : state) {
    HierarchicalEvaluator<3> ev(h.space(), 3, false, h.coefs());
    benchmark::DoNotOptimize(&ev);
  }
  state.counters["elements"] = h.space().num_elements();
}

}  // namespace

BENCHMARK(corner_levels)->Name("thb_corner_10_levels/cells_per_dir")->Arg(1)->Arg(4)->Unit(benchmark::kMillisecond);
BENCHMARK(value)->Name("thb_eval_value")->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(first_derivatives)->Name("thb_eval_first_derivatives")->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(build_evaluator)->Name("thb_build_evaluator")->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
