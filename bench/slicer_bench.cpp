// Graded-material slicing, the two tables of the reference (seed 001: Ezair, Elber, Dikovsky), on trivar's
// own models with two materials blending radially, on the reference printer's tray bitmap: 2944 x 1466
// pixels at 600 x 300 dpi (124.6 x 124.1 mm, the model centred), 0.027 mm layers around the model's middle.
//   BM_TracingMethod/m/t: tracing method m (0 none, 1 previous point, 2 previous line, 3 full) on t threads:
//     seconds, full-solve percentage (robust point inversions per inside pixel).
//   BM_Model/k/t: model k (0 ball r 20, 1 torus 40/12, 2 cylinder r 20 h 40, 3 ball r 60 filling the tray)
//     with full tracing: seconds per layer, inside pixels per second.
// The reference needed 0.7-10.4 s per slice of this size on 4 threads and reached 0.0044 % full solves.
#include <benchmark/benchmark.h>

#include "trivar/am/slicer.hpp"
#include "trivar/model/ball.hpp"
#include "trivar/model/cylinder.hpp"
#include "trivar/model/torus.hpp"

using namespace trivar;

namespace {

// Two materials: M1 at the centre line (or point) blending into M2 at distance `scale`.
VModel graded(const CellComplex& cells, const std::string& rho) {
  VModel v;
  for (const auto& c : cells) {
    VCell cell(c);
    cell.set_attribute("material", Attribute::expression({"1 - min(1, " + rho + ")", "min(1, " + rho + ")"},
                                                         Attribute::Space::model));
    v.add_cell(std::move(cell));
  }
  v.glue();
  return v;
}

const VModel& model(int k) {
  static const VModel models[] = {
      graded(make_ball({.radius = 20}), "sqrt(x*x + y*y + z*z) / 20"),
      graded(make_torus({.major_radius = 40, .minor_radius = 12}), "abs(sqrt(x*x + y*y) - 40) / 12"),
      graded(make_cylinder({.radius = 20, .height = 40}), "sqrt(x*x + y*y) / 20"),
      graded(make_ball({.radius = 60}), "sqrt(x*x + y*y + z*z) / 60"),
  };
  return models[k];
}

const char* const kModelNames[] = {"ball r20", "torus 40/12", "cylinder r20 h40", "ball r60"};
const char* const kMethodNames[] = {"none", "previous-point", "previous-line", "full"};

// The reference tray, centred on the model's bounding box; `layers` layers of 0.027 mm around its middle.
am::SliceOptions tray(const VModel& m, int layers) {
  am::SliceOptions o;
  o.dpi_x = 600;
  o.dpi_y = 300;
  o.image_size = {{2944, 1466}};
  const Box<3> b = m.bounding_box();
  const double cx = 0.5 * (b.lo[0] + b.hi[0]), cy = 0.5 * (b.lo[1] + b.hi[1]), cz = 0.5 * (b.lo[2] + b.hi[2]);
  o.origin = {{cx - 0.5 * 2944 * 25.4 / 600, cy - 0.5 * 1466 * 25.4 / 300}};
  o.z_range = {{cz - 0.5 * layers * o.layer_thickness, cz + 0.5 * layers * o.layer_thickness}};
  return o;
}

void run(benchmark::State& state, const VModel& m, am::SliceOptions o) {
  o.threads = static_cast<int>(state.range(1));
  am::SliceSummary s;
  for (auto _ : state) s = am::slice_model(m, o, am::LayerConsumer{});
  state.counters["layers"] = s.layers;
  state.counters["s_per_layer"] = s.seconds / s.layers;
  state.counters["inside_px"] = static_cast<double>(s.inside_pixels);
  state.counters["inside_px_per_s"] = s.inside_pixels_per_second();
  state.counters["full_solve_pct"] = s.full_solve_percent();
  state.counters["max_residual"] = s.max_residual;
}

void BM_TracingMethod(benchmark::State& state) {
  const auto method = static_cast<am::Tracing>(state.range(0));
  state.SetLabel(std::string(kMethodNames[state.range(0)]) + ", ball r20");
  am::SliceOptions o = tray(model(0), method == am::Tracing::none ? 1 : 4);
  o.tracing = method;
  run(state, model(0), o);
}
BENCHMARK(BM_TracingMethod)
    ->ArgsProduct({{0, 1, 2, 3}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->UseRealTime();

void BM_Model(benchmark::State& state) {
  state.SetLabel(kModelNames[state.range(0)]);
  run(state, model(static_cast<int>(state.range(0))), tray(model(static_cast<int>(state.range(0))), 8));
}
BENCHMARK(BM_Model)->ArgsProduct({{0, 1, 2, 3}, {1, 2}})->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
