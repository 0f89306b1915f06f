// Throughput of the ISO 10303-21 reader on a generated file of about 100 MB: CARTESIAN_POINTs and
// B_SPLINE_SURFACE_WITH_KNOTS instances in the proportions of a CAD model's geometry, plus topology-like
// instances that a geometry filter drops. Target: >= 50 MB/s parsing from disk, all instances kept.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "trivar/io/step/parser.hpp"
#include "trivar/io/step/real_format.hpp"
#include "trivar/io/step/step_file.hpp"

using namespace trivar::io::step;

namespace {

// Writes the file once per process; 16 x 16 control-point surfaces with their own points.
const std::string& generated_file() {
  static const std::string path = [] {
    const std::string p =
        (std::filesystem::temp_directory_path() / ("trivar_step_bench_" + std::to_string(::getpid()) + ".stp")).string();
    std::ofstream out(p, std::ios::binary);
    out << "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('bench'),'2;1');\n"
           "FILE_NAME('bench.stp','2026-01-01T00:00:00',(''),(''),'trivar','trivar','');\n"
           "FILE_SCHEMA(('AP242_MANAGED_MODEL_BASED_3D_ENGINEERING_MIM_LF { 1 0 10303 442 1 1 4 }'));\nENDSEC;\nDATA;\n";
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> coord(-500.0, 500.0);
    std::uint64_t id = 1;
    std::string line;
    auto ref = [&](std::uint64_t r) {  // appends piecewise: GCC 12 warns falsely on "#" + std::string
      line += '#';
      line += std::to_string(r);
    };
    const std::uint64_t target = 100u << 20;
    std::uint64_t written = 0;
    constexpr int n = 16;
    while (written < target) {
      line.clear();
      const std::uint64_t first = id;
      for (int k = 0; k < n * n; ++k) {
        ref(id++);
        line += "=CARTESIAN_POINT('',(";
        for (int c = 0; c < 3; ++c) {
          if (c) line += ',';
          append_real(line, coord(rng));
        }
        line += "));\n";
      }
      ref(id++);
      line += "=B_SPLINE_SURFACE_WITH_KNOTS('',3,3,(";
      for (int i = 0; i < n; ++i) {
        line += i ? ",(" : "(";
        for (int j = 0; j < n; ++j) {
          if (j) line += ',';
          ref(first + static_cast<std::uint64_t>(i * n + j));
        }
        line += ')';
      }
      line += "),.UNSPECIFIED.,.F.,.F.,.F.,\n  ";
      for (int dir = 0; dir < 2; ++dir) {
        line += "(4,";
        for (int k = 0; k < n - 4; ++k) line += "1,";
        line += "4),";
      }
      for (int dir = 0; dir < 2; ++dir) {
        line += "(0.,";
        for (int k = 1; k <= n - 4; ++k) {
          append_real(line, k / double(n - 3));
          line += ',';
        }
        line += "1.),";
      }
      line += ".UNSPECIFIED.);\n";
      ref(id);
      line += "=ADVANCED_FACE('',(";
      ref(id + 1);
      line += "),";
      ref(id - 1);
      line += ",.T.);\n";
      ref(id + 1);
      line += "=FACE_BOUND('',";
      ref(first);
      line += ",.T.);\n";
      id += 2;
      out << line;
      written += line.size();
    }
    out << "ENDSEC;\nEND-ISO-10303-21;\n";
    return p;
  }();
  return path;
}

void report(benchmark::State& state) {
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) *
                          static_cast<int64_t>(std::filesystem::file_size(generated_file())));
}

void BM_ParseKeepAll(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(read_exchange_file(generated_file()));
  report(state);
}
BENCHMARK(BM_ParseKeepAll)->Unit(benchmark::kMillisecond)->Iterations(3);

// What the geometry mapper does: keep only the surfaces and points, skip the topology unparsed.
void BM_ParseGeometryOnly(benchmark::State& state) {
  ReadOptions o;
  o.keep = [](std::string_view k) { return k == "CARTESIAN_POINT" || k == "B_SPLINE_SURFACE_WITH_KNOTS"; };
  for (auto _ : state) benchmark::DoNotOptimize(read_exchange_file(generated_file(), o));
  report(state);
}
BENCHMARK(BM_ParseGeometryOnly)->Unit(benchmark::kMillisecond)->Iterations(3);

// Only the surfaces: the points (most of the bytes) go through the skip path.
void BM_ParseSurfacesOnly(benchmark::State& state) {
  ReadOptions o;
  o.keep = [](std::string_view k) { return k == "B_SPLINE_SURFACE_WITH_KNOTS"; };
  for (auto _ : state) benchmark::DoNotOptimize(read_exchange_file(generated_file(), o));
  report(state);
}
BENCHMARK(BM_ParseSurfacesOnly)->Unit(benchmark::kMillisecond)->Iterations(3);

// The whole import: parse with the mapper's filter and map every surface to a TensorSpline<2> (validated),
// with the faces that use it.
void BM_ReadStepGeometry(benchmark::State& state) {
  std::size_t surfaces = 0;
  for (auto _ : state) surfaces = read_step(generated_file()).splines.size();
  report(state);
  state.counters["surfaces_per_s"] =
      benchmark::Counter(static_cast<double>(surfaces) * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ReadStepGeometry)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  std::filesystem::remove(generated_file());
  return 0;
}
