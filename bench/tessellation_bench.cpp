// Boundary tessellation of the exact primitives for STL / 3MF / AMF export, one thread.
//   BM_Tessellate/k/e: model k (0 ball r 1, 1 cylinder r 1 h 2, 2 torus 2 / 0.5) at chordal tolerance
//     10^-e / 2 (e = 2: 0.005 ... ): seconds per tessellation, triangles and triangles per second.
#include <benchmark/benchmark.h>

#include <cmath>

#include "trivar/model/ball.hpp"
#include "trivar/model/cylinder.hpp"
#include "trivar/model/model_tessellation.hpp"
#include "trivar/model/torus.hpp"

using namespace trivar;

namespace {

VModel glued(const CellComplex& cells) {
  VModel v;
  for (const auto& c : cells) v.add_cell(VCell(c));
  v.glue();
  return v;
}

const VModel& model(int k) {
  static const VModel models[] = {
      glued(make_ball({.radius = 1})),
      glued(make_cylinder({.radius = 1, .height = 2})),
      glued(make_torus({.major_radius = 2, .minor_radius = 0.5})),
  };
  return models[k];
}

void BM_Tessellate(benchmark::State& state) {
  const VModel& m = model(static_cast<int>(state.range(0)));
  const double tol = 0.5 * std::pow(10.0, -static_cast<double>(state.range(1)));
  std::size_t triangles = 0;
  for (auto _ : state) {
    const ModelTessellation t = tessellate_boundary(m, {.chordal_tolerance = tol});
    triangles = t.mesh.triangles.size();
    benchmark::DoNotOptimize(t.mesh.vertices.data());
  }
  state.counters["triangles"] = static_cast<double>(triangles);
  state.counters["triangles/s"] =
      benchmark::Counter(static_cast<double>(triangles), benchmark::Counter::kIsIterationInvariantRate);
}

}  // namespace

BENCHMARK(BM_Tessellate)->ArgsProduct({{0, 1, 2}, {1, 2, 3}})->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
