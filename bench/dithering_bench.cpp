// Dithering throughput on one full printer layer (2944 x 1466 pixels, the reference paper's bitmap) with three
// materials blending smoothly over an elliptic part that fills most of the plate: pixels per second for error
// diffusion and ordered dithering, and the palette PNG encoding of the result.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "trivar/am/dithering.hpp"
#include "trivar/io/png_writer.hpp"

using namespace trivar;

namespace {

constexpr int width = 2944, height = 1466;

const FractionImage& layer() {
  static const FractionImage img = [] {
    FractionImage f(width, height, 3);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const double u = (x - width / 2.0) / (0.48 * width), v = (y - height / 2.0) / (0.48 * height);
        if (u * u + v * v >= 1) continue;
        const double r = std::sqrt(u * u + v * v);
        f(x, y, 0) = static_cast<float>(1 - r);
        f(x, y, 1) = static_cast<float>(r * (0.5 + 0.5 * std::sin(6 * u)));
        f(x, y, 2) = static_cast<float>(r * (0.5 - 0.5 * std::sin(6 * u)));
      }
    return f;
  }();
  return img;
}

void run(benchmark::State& state, am::DitherMethod method) {
  const auto& in = layer();
  LabelImage out;
  for (auto _ : state) {
    am::dither(in, out, {method, 16});
    benchmark::DoNotOptimize(out.data().data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * width * height);
  state.counters["pixels/s"] =
      benchmark::Counter(static_cast<double>(width) * height, benchmark::Counter::kIsIterationInvariantRate);
}

void BM_ErrorDiffusion3(benchmark::State& state) { run(state, am::DitherMethod::error_diffusion); }
BENCHMARK(BM_ErrorDiffusion3)->Unit(benchmark::kMillisecond);

void BM_Ordered3(benchmark::State& state) { run(state, am::DitherMethod::ordered); }
BENCHMARK(BM_Ordered3)->Unit(benchmark::kMillisecond);

void BM_PalettePng(benchmark::State& state) {
  const auto labels = am::dither(layer());
  const MaterialTable materials({{"a", {255, 0, 0, 255}}, {"b", {0, 255, 0, 255}}, {"c", {0, 0, 255, 255}}});
  const auto palette = io::material_palette(materials);
  const std::string path =
      (std::filesystem::temp_directory_path() / ("trivar_dither_bench_" + std::to_string(::getpid()) + ".png")).string();
  for (auto _ : state) io::write_palette_png(path, labels, palette);
  state.counters["pixels/s"] =
      benchmark::Counter(static_cast<double>(width) * height, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["bytes"] = static_cast<double>(std::filesystem::file_size(path));
  std::filesystem::remove(path);
}
BENCHMARK(BM_PalettePng)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
