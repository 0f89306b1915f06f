// STEP part -> trimmed V-model: OpenCASCADE reading, NURBS conversion, tessellation, trivar mapping and the
// exact-boundary volume; classification and slicing rows of a trimmed model.
#include <benchmark/benchmark.h>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <STEPControl_Writer.hxx>
#include <TopTools_ListOfShape.hxx>
#include <unistd.h>

#include <filesystem>
#include <random>

#include "trivar/cad/step_import.hpp"
#include "trivar/am/slicer.hpp"
#include "trivar/iga/trimmed_space.hpp"

namespace {

// A 200 x 200 x 10 plate with n x n through holes (n^2 + 6 faces: planes and cylinders), written by
// OpenCASCADE; a stand-in for a machined part of a few hundred faces.
const std::string& plate(int n) {
  static std::map<int, std::string> files;
  auto& path = files[n];
  if (!path.empty()) return path;
  Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
  TopTools_ListOfShape tools;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      tools.Append(BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(200.0 * (i + 0.5) / n, 200.0 * (j + 0.5) / n, -1), gp_Dir(0, 0, 1)),
                                            40.0 / n, 12).Shape());
  BRepAlgoAPI_Cut cut;
  TopTools_ListOfShape args;
  args.Append(BRepPrimAPI_MakeBox(200, 200, 10).Shape());
  cut.SetArguments(args);
  cut.SetTools(tools);
  cut.Build();
  path = (std::filesystem::temp_directory_path() / ("trivar_bench_plate_" + std::to_string(n) + "_" +
                                                    std::to_string(::getpid()) + ".stp")).string();
  STEPControl_Writer w;
  w.Transfer(cut.Shape(), STEPControl_AsIs);
  w.Write(path.c_str());
  return path;
}

void BM_StepToTrimmedModel(benchmark::State& state) {
  const std::string& path = plate(static_cast<int>(state.range(0)));
  double volume = 0;
  std::size_t faces = 0;
  for (auto _ : state) {
    const trivar::cad::StepImport im = trivar::cad::import_step(path);
    volume = im.solids.at(0).solid->volume();
    faces = im.solids[0].solid->boundary().faces.size();
  }
  state.counters["faces"] = static_cast<double>(faces);
  state.counters["file_kB"] = static_cast<double>(std::filesystem::file_size(path)) / 1024;
  state.counters["volume"] = volume;
}
// Wall time is the figure (the validity check runs beside the conversion, the meshing on both cores); the CPU
// column counts every thread.
BENCHMARK(BM_StepToTrimmedModel)->Arg(4)->Arg(12)->Arg(20)->Arg(28)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();

void BM_ContainsRandomPoints(benchmark::State& state) {
  const trivar::cad::StepImport im = trivar::cad::import_step(plate(12));
  const trivar::TrimmedSolid& s = *im.solids.at(0).solid;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> x(0, 200), z(0, 10);
  std::vector<std::array<double, 3>> pts(100000);
  for (auto& p : pts) p = {x(rng), x(rng), z(rng)};
  for (auto _ : state) {
    int inside = 0;
    for (const auto& p : pts) inside += s.contains(p);
    benchmark::DoNotOptimize(inside);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(pts.size()));
}
BENCHMARK(BM_ContainsRandomPoints)->Unit(benchmark::kMillisecond);

// Slicing the ball of radius 20 mm as a trimmed model (OpenCASCADE's sphere through STEP, one box cell trimmed
// by it) exactly as bench_slicer's BM_Model slices the spline ball ("ball r20": the same radial two-material
// blend, the reference tray of 2944 x 1466 pixels at 600 x 300 dpi, 8 layers of 0.027 mm around the middle),
// so the inside pixels per second compare directly.
void BM_SliceTrimmedBall(benchmark::State& state) {
  static const trivar::VModel m = [] {
    Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
    const std::string path = (std::filesystem::temp_directory_path() /
                              ("trivar_bench_ball_" + std::to_string(::getpid()) + ".stp")).string();
    STEPControl_Writer w;
    w.Transfer(BRepPrimAPI_MakeSphere(gp_Pnt(0, 0, 0), 20).Shape(), STEPControl_AsIs);
    w.Write(path.c_str());
    const trivar::cad::StepImport im = trivar::cad::import_step(path);
    std::filesystem::remove(path);
    const auto solid = im.solids.at(0).solid;
    trivar::VModel v;
    trivar::VCell cell(trivar::identity_geometry(solid->bounding_box(), 1, 1), solid);
    const std::string rho = "sqrt(x*x + y*y + z*z) / 20";
    cell.set_attribute("material", trivar::Attribute::expression({"1 - min(1, " + rho + ")", "min(1, " + rho + ")"},
                                                                 trivar::Attribute::Space::model));
    v.add_cell(std::move(cell));
    v.glue();
    return v;
  }();
  trivar::am::SliceOptions o;
  o.dpi_x = 600;
  o.dpi_y = 300;
  o.image_size = {{2944, 1466}};
  o.origin = {{-0.5 * 2944 * 25.4 / 600, -0.5 * 1466 * 25.4 / 300}};
  o.z_range = {{-4 * o.layer_thickness, 4 * o.layer_thickness}};
  o.threads = static_cast<int>(state.range(0));
  trivar::am::SliceSummary s;
  for (auto _ : state) s = trivar::am::slice_model(m, o, trivar::am::LayerConsumer{});
  state.counters["s_per_layer"] = s.seconds / s.layers;
  state.counters["inside_px"] = static_cast<double>(s.inside_pixels);
  state.counters["inside_px_per_s"] = s.inside_pixels_per_second();
}
BENCHMARK(BM_SliceTrimmedBall)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();

// The detrimmed analysis space of the 4 x 4 plate (quadratics, n^3 elements on its box): element placement,
// cut-element volume rules and trimming-boundary points; the cut elements per second are the figure.
void BM_TrimmedSpace(benchmark::State& state) {
  const trivar::cad::StepImport im = trivar::cad::import_step(plate(4));
  const trivar::TrimmedSolid& s = *im.solids.at(0).solid;
  const int n = static_cast<int>(state.range(0));
  std::int64_t cut = 0, points = 0;
  for (auto _ : state) {
    const trivar::RefinedSpace<3> space = trivar::trimmed_space(s, trivar::analysis_box(s), 2, n, 1);
    cut = points = 0;
    for (const auto& el : space.elements) {
      cut += !el.rule.empty();
      points += static_cast<std::int64_t>(el.rule.size() + el.trim_sides.size());
    }
  }
  state.counters["cut_elements"] = static_cast<double>(cut);
  state.counters["points_per_cut"] = cut ? static_cast<double>(points) / static_cast<double>(cut) : 0.0;
  state.SetItemsProcessed(state.iterations() * cut);
}
BENCHMARK(BM_TrimmedSpace)->Arg(4)->Arg(8)->Arg(16)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
