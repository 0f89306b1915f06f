// STEP part -> trimmed V-model: OpenCASCADE reading, NURBS conversion, tessellation, trivar mapping and the
// exact-boundary volume; classification and slicing rows of a trimmed model.
#include <benchmark/benchmark.h>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <STEPControl_Writer.hxx>
#include <TopTools_ListOfShape.hxx>
#include <unistd.h>

#include <filesystem>
#include <random>

#include "trivar/cad/step_import.hpp"

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
BENCHMARK(BM_StepToTrimmedModel)->Arg(4)->Arg(12)->Arg(20)->Unit(benchmark::kMillisecond);

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

}  // namespace

BENCHMARK_MAIN();
