// Throughput of the spline file formats on a tricubic volume with 16^3 elements (19^3 rational control
// points): what a CLI conversion or a ParaView export costs.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "trivar/io/g2_format.hpp"
#include "trivar/io/json_format.hpp"
#include "trivar/io/vtk_writer.hpp"

using namespace trivar;

namespace {

SplineVolume rational_volume() {
  std::array<KnotVector, 3> kv;
  for (auto& k : kv) k = KnotVector::open_uniform(3, 16);
  const int n = kv[0].size();
  const auto g = kv[0].greville();
  std::vector<double> pts, w;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        pts.insert(pts.end(), {g[i] + 0.05 * std::sin(3 * g[j]), g[j], g[k] + 0.05 * std::sin(3 * g[i])});
        w.push_back(1.0 + 0.3 * g[i] * g[j]);
      }
  return SplineVolume::from_cartesian(kv, 3, pts, w);
}

std::string temp_file(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("trivar_io_bench_" + std::to_string(::getpid()) + name)).string();
}

void BM_WriteG2(benchmark::State& state) {
  const std::vector<AnySpline> v{rational_volume()};
  const std::string path = temp_file(".g2");
  for (auto _ : state) io::write_g2(path, v);
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) *
                          static_cast<int64_t>(std::filesystem::file_size(path)));
  std::filesystem::remove(path);
}
BENCHMARK(BM_WriteG2)->Unit(benchmark::kMillisecond);

void BM_ReadG2(benchmark::State& state) {
  const std::string path = temp_file(".g2");
  io::write_g2(path, {rational_volume()});
  for (auto _ : state) benchmark::DoNotOptimize(io::read_g2(path));
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) *
                          static_cast<int64_t>(std::filesystem::file_size(path)));
  std::filesystem::remove(path);
}
BENCHMARK(BM_ReadG2)->Unit(benchmark::kMillisecond);

void BM_WriteJson(benchmark::State& state) {
  const std::vector<AnySpline> v{rational_volume()};
  const std::string path = temp_file(".json");
  for (auto _ : state) io::write_json(path, v);
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) *
                          static_cast<int64_t>(std::filesystem::file_size(path)));
  std::filesystem::remove(path);
}
BENCHMARK(BM_WriteJson)->Unit(benchmark::kMillisecond);

void BM_ReadJson(benchmark::State& state) {
  const std::string path = temp_file(".json");
  io::write_json(path, {rational_volume()});
  for (auto _ : state) benchmark::DoNotOptimize(io::read_json(path));
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) *
                          static_cast<int64_t>(std::filesystem::file_size(path)));
  std::filesystem::remove(path);
}
BENCHMARK(BM_ReadJson)->Unit(benchmark::kMillisecond);

// Sampled (n = 4: 64^3 hexahedra) and Bezier (16^3 cells of 64 points) VTU export.
void BM_WriteVtu(benchmark::State& state) {
  const AnySpline v = rational_volume();
  const std::string path = temp_file(".vtu");
  io::VtkOptions opts;
  opts.bezier_cells = state.range(0) == 1;
  for (auto _ : state) io::write_vtu(path, v, opts);
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) *
                          static_cast<int64_t>(std::filesystem::file_size(path)));
  std::filesystem::remove(path);
}
BENCHMARK(BM_WriteVtu)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
