// STEP part -> trimmed V-model: OpenCASCADE reading, NURBS conversion, tessellation, trivar mapping and the
// exact-boundary volume; classification and slicing rows of a trimmed model.
#include <benchmark/benchmark.h>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRep_Tool.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepFilletAPI_MakeFillet.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <Geom_BezierSurface.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <STEPControl_Writer.hxx>
#include <TopTools_ListOfShape.hxx>
#include <unistd.h>

#include <filesystem>
#include <random>

#include "trivar/cad/offset_fit.hpp"
#include "trivar/cad/step_import.hpp"
#include "trivar/am/slicer.hpp"
#include "trivar/iga/trimmed_space.hpp"
#include "trivar/model/closure_defect.hpp"
#include "trivar/model/trimmed_integral.hpp"

namespace {

// The STEP files the benchmarks wrote, removed when the program ends.
struct WrittenFiles {
  std::vector<std::string> paths;
  ~WrittenFiles() {
    for (const std::string& p : paths) std::filesystem::remove(p);
  }
};
WrittenFiles written;

std::string write_step(const TopoDS_Shape& s, const std::string& name) {
  const std::string path =
      (std::filesystem::temp_directory_path() / ("trivar_bench_" + name + "_" + std::to_string(::getpid()) + ".stp")).string();
  STEPControl_Writer w;
  w.Transfer(s, STEPControl_AsIs);
  w.Write(path.c_str());
  written.paths.push_back(path);
  return path;
}

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
  path = write_step(cut.Shape(), "plate_" + std::to_string(n));
  return path;
}

// A machined block, 40 mm thick, on an n x n grid of 40 mm cells alternating between
// - a pocket 24 x 18 x 12 mm whose vertical edges are rounded with radius 5 (cylinders) and floor edges with a
//   radius growing from 1.5 to 2.5 along each edge (B-spline blends, and B-spline corner patches), and
// - a boss of radius 8, 10 mm high, with a fillet of radius 3 at its foot (a torus) and a hole of radius 4
//   through boss and block,
// and two cross holes of radius 3 along x through the whole block at mid-height (cylinders meeting the boss
// holes: intersection curves that are no iso-lines). Planes, cylinders, tori and B-spline blends with a few
// loops per face, written by OpenCASCADE: a stand-in for a real machined part.
const std::string& machined_part(int n) {
  static std::map<int, std::string> files;
  auto& path = files[n];
  if (!path.empty()) return path;
  Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
  const double cell = 40, size = cell * n, depth = 12;
  const TopoDS_Shape pocket = [&] {
    const TopoDS_Shape box = BRepPrimAPI_MakeBox(gp_Pnt(-12, -9, 0), 24, 18, 30).Shape();
    BRepFilletAPI_MakeFillet f(box);
    for (TopExp_Explorer e(box, TopAbs_EDGE); e.More(); e.Next()) {
      double first = 0, last = 0;
      const TopoDS_Edge& edge = TopoDS::Edge(e.Current());
      const Handle(Geom_Curve) c = BRep_Tool::Curve(edge, first, last);
      const gp_Pnt a = c->Value(first), b = c->Value(last);
      if (std::abs(a.Z() - b.Z()) > 1)
        f.Add(5, edge);  // vertical
      else if (a.Z() < 1e-9 && b.Z() < 1e-9)
        f.Add(1.5, 2.5, edge);  // floor: a radius growing along the edge (B-spline blends)
    }
    return f.Shape();
  }();
  const double foot = 3, boss_r = 8, boss_h = 10;
  // The boss with its foot fillet: a cylinder on a collar of radius boss_r + foot, height foot, whose torus
  // (centred at the collar's outer top edge) is cut away.
  const TopoDS_Shape boss = [&] {
    const TopoDS_Shape cyl = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -1), gp_Dir(0, 0, 1)), boss_r, boss_h + 1).Shape();
    const TopoDS_Shape collar = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -1), gp_Dir(0, 0, 1)), boss_r + foot, foot + 1).Shape();
    const TopoDS_Shape torus = BRepPrimAPI_MakeTorus(gp_Ax2(gp_Pnt(0, 0, foot), gp_Dir(0, 0, 1)), boss_r + foot, foot).Shape();
    return BRepAlgoAPI_Fuse(cyl, BRepAlgoAPI_Cut(collar, torus).Shape()).Shape();
  }();
  TopTools_ListOfShape cut_tools, bosses;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      gp_Trsf at;
      at.SetTranslation(gp_Vec(cell * (i + 0.5), cell * (j + 0.5), 0));
      if ((i + j) % 2 == 0) {
        gp_Trsf down;
        down.SetTranslation(gp_Vec(cell * (i + 0.5), cell * (j + 0.5), cell - depth));
        cut_tools.Append(BRepBuilderAPI_Transform(pocket, down, true).Shape());
      } else {
        gp_Trsf up;
        up.SetTranslation(gp_Vec(cell * (i + 0.5), cell * (j + 0.5), cell));
        bosses.Append(BRepBuilderAPI_Transform(boss, up, true).Shape());
        cut_tools.Append(BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(cell * (i + 0.5), cell * (j + 0.5), -1), gp_Dir(0, 0, 1)), 4,
                                                  cell + boss_h + 2).Shape());
      }
    }
  for (double y : {cell * 1.5, cell * (n - 1.5)})
    cut_tools.Append(BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(-1, y, cell / 2), gp_Dir(1, 0, 0)), 3, size + 2).Shape());
  BRepAlgoAPI_Fuse fuse;
  TopTools_ListOfShape block;
  block.Append(BRepPrimAPI_MakeBox(size, size, cell).Shape());
  fuse.SetArguments(block);
  fuse.SetTools(bosses);
  fuse.Build();
  BRepAlgoAPI_Cut cut;
  TopTools_ListOfShape fused;
  fused.Append(fuse.Shape());
  cut.SetArguments(fused);
  cut.SetTools(cut_tools);
  cut.Build();
  path = write_step(cut.Shape(), "machined_" + std::to_string(n));
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

void BM_MachinedPartToTrimmedModel(benchmark::State& state) {
  const std::string& path = machined_part(static_cast<int>(state.range(0)));
  // OpenCASCADE's volume of the part as read, once outside the timed imports (which, like `trivar info` and
  // `make vmodel`, leave it out by default).
  const double kernel = trivar::cad::import_step(path, {.kernel_volume = true}).solids.at(0).kernel_volume.value();
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
  state.counters["rel_diff_occt"] = std::abs(volume - kernel) / kernel;
}
BENCHMARK(BM_MachinedPartToTrimmedModel)->Arg(3)->Arg(7)->Arg(8)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();

// Fitting the offset of a free-form surface (cad/offset_fit): the offset by 0.5 of a saddle-like bicubic
// Bezier patch over 9 x 9 units, to 1e-{arg} model units (the import asks for 1e-9 of the solid's size).
void BM_OffsetSurfaceFit(benchmark::State& state) {
  TColgp_Array2OfPnt poles(1, 4, 1, 4);
  for (int i = 1; i <= 4; ++i)
    for (int j = 1; j <= 4; ++j) poles(i, j) = gp_Pnt(3.0 * i, 3.0 * j, ((i + j) % 3 - 1) * 2.5 + 0.3 * i * j);
  const Handle(Geom_Surface) patch = new Geom_BezierSurface(poles);
  const double tol = std::pow(10.0, -static_cast<double>(state.range(0)));
  int coefs = 0;
  for (auto _ : state) coefs = trivar::cad::fit_offset_surface(patch, 0.5, {{0, 0}, {1, 1}}, tol).surface.num_coefs();
  state.counters["control_points"] = coefs;
}
BENCHMARK(BM_OffsetSurfaceFit)->Arg(6)->Arg(9)->Unit(benchmark::kMillisecond);

// trivar's exact volume alone (`trimmed_volume` on the imported boundary, on all threads as in the import):
// Arg 0 the 28 x 28 plate, Arg n > 0 the machined part n. The part is read once, outside the timing.
void BM_ExactVolume(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const trivar::cad::StepImport im = trivar::cad::import_step(n == 0 ? plate(28) : machined_part(n));
  const trivar::TrimmedBoundary& b = im.solids.at(0).solid->boundary();
  double volume = 0;
  for (auto _ : state) volume = trivar::trimmed_volume(b);
  std::size_t rational = 0;
  for (const auto& f : b.faces) rational += f.surface.is_rational();
  state.counters["faces"] = static_cast<double>(b.faces.size());
  state.counters["rational_faces"] = static_cast<double>(rational);
  state.counters["volume"] = volume;
}
BENCHMARK(BM_ExactVolume)->Arg(0)->Arg(7)->Arg(8)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();

// The closure defect the import adds per solid (`closure_defect`: the area vector's three components by the
// volume's quadrature, the mesh's area, the edges' lengths) on the boundaries BM_ExactVolume integrates.
void BM_ClosureDefect(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const trivar::cad::StepImport im = trivar::cad::import_step(n == 0 ? plate(28) : machined_part(n));
  const trivar::TrimmedBoundary& b = im.solids.at(0).solid->boundary();
  trivar::ClosureDefect d;
  for (auto _ : state) d = trivar::closure_defect(b);
  state.counters["faces"] = static_cast<double>(b.faces.size());
  state.counters["relative"] = d.relative;
}
BENCHMARK(BM_ClosureDefect)->Arg(0)->Arg(7)->Arg(8)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();

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
