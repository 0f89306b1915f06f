// Throughput of the spline file formats on a tricubic volume with 16^3 elements (19^3 rational control
// points): what a CLI conversion or a ParaView export costs.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "bench_volumes.hpp"
#include "trivar/io/g2_format.hpp"
#include "trivar/io/json_format.hpp"
#include "trivar/io/vtk_writer.hpp"

using namespace trivar;

namespace {

std::string temp_file(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("trivar_io_bench_" + std::to_string(::getpid()) + name)).string();
}

void BM_WriteG2(benchmark::State& state) {
  const std::vector<AnySpline> v{bench::perturbed_cube(3, 16, 0.05, true)};
  const std::string path = temp_file(".g2");
  for (auto _ : state) io::write_g2(path, v);
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) *
                          static_cast<int64_t>(std::filesystem::file_size(path)));
  std::filesystem::remove(path);
}
BENCHMARK(BM_WriteG2)->Unit(benchmark::kMillisecond);

void BM_ReadG2(benchmark::State& state) {
  const std::string path = temp_file(".g2");
  io::write_g2(path, {bench::perturbed_cube(3, 16, 0.05, true)});
  for (auto _ : state) benchmark::DoNotOptimize(io::read_g2(path));
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) *
                          static_cast<int64_t>(std::filesystem::file_size(path)));
  std::filesystem::remove(path);
}
BENCHMARK(BM_ReadG2)->Unit(benchmark::kMillisecond);

void BM_WriteJson(benchmark::State& state) {
  const std::vector<AnySpline> v{bench::perturbed_cube(3, 16, 0.05, true)};
  const std::string path = temp_file(".json");
  for (auto _ : state) io::write_json(path, v);
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) *
                          static_cast<int64_t>(std::filesystem::file_size(path)));
  std::filesystem::remove(path);
}
BENCHMARK(BM_WriteJson)->Unit(benchmark::kMillisecond);

void BM_ReadJson(benchmark::State& state) {
  const std::string path = temp_file(".json");
  io::write_json(path, {bench::perturbed_cube(3, 16, 0.05, true)});
  for (auto _ : state) benchmark::DoNotOptimize(io::read_json(path));
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) *
                          static_cast<int64_t>(std::filesystem::file_size(path)));
  std::filesystem::remove(path);
}
BENCHMARK(BM_ReadJson)->Unit(benchmark::kMillisecond);

// Sampled (n = 4: 64^3 hexahedra) and Bezier (16^3 cells of 64 points) VTU export.
void BM_WriteVtu(benchmark::State& state) {
  const AnySpline v = bench::perturbed_cube(3, 16, 0.05, true);
  const std::string path = temp_file(".vtu");
  io::VtkOptions opts;
  opts.cells = state.range(0) == 1 ? io::VtkCells::bezier : io::VtkCells::sampled;
  for (auto _ : state) io::write_vtu(path, v, opts);
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) *
                          static_cast<int64_t>(std::filesystem::file_size(path)));
  std::filesystem::remove(path);
}
BENCHMARK(BM_WriteVtu)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
