// Graded-material slicing of a ball of radius 20 mm whose two materials blend from the centre to the surface,
// at 600 x 600 dpi (0.0423 mm pixels): four layers around the equator (946 x 946 pixels, ~7e5 inside each) and
// the whole ball at 2 mm layers, on 1 and 2 threads. Counters: inside pixels per second and the percentage of
// pixels that needed the robust point inversion (full solves). The reference (seed 001) needed 0.7-10.4 s per
// 2944 x 1466 slice on 4 threads and reached 0.0044 % full solves.
#include <benchmark/benchmark.h>

#include "trivar/am/slicer.hpp"
#include "trivar/model/ball.hpp"

using namespace trivar;

namespace {

const VModel& graded_ball() {
  static const VModel m = [] {
    VModel v;
    for (const auto& c : make_ball({20.0})) {
      VCell cell(c);
      cell.set_attribute("material", Attribute::expression({"sqrt(x * x + y * y + z * z) / 20",
                                                            "1 - sqrt(x * x + y * y + z * z) / 20"},
                                                           Attribute::Space::model));
      v.add_cell(std::move(cell));
    }
    v.glue();
    return v;
  }();
  return m;
}

void run(benchmark::State& state, am::SliceOptions o) {
  o.threads = static_cast<int>(state.range(0));
  am::SliceSummary s;
  for (auto _ : state) s = am::slice_model(graded_ball(), o, am::LayerConsumer{});
  state.counters["inside_px_per_s"] = s.inside_pixels_per_second();
  state.counters["full_solve_pct"] = s.full_solve_percent();
  state.counters["inside_px"] = static_cast<double>(s.inside_pixels);
  state.counters["layers"] = s.layers;
  state.counters["max_residual"] = s.max_residual;
}

void BM_SliceEquatorLayers(benchmark::State& state) {
  am::SliceOptions o;
  o.z_range = {{-0.054, 0.054}};  // 4 layers of 0.027 mm
  run(state, o);
}
BENCHMARK(BM_SliceEquatorLayers)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();

void BM_SliceWholeBall2mm(benchmark::State& state) {
  am::SliceOptions o;
  o.layer_thickness = 2.0;
  o.z_range = {{-20.0, 20.0}};
  run(state, o);
}
BENCHMARK(BM_SliceWholeBall2mm)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
