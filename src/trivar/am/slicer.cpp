#include "trivar/am/slicer.hpp"

#include <chrono>
#include <cstdio>
#include <exception>
#include <mutex>

#include "trivar/am/layer_slicer.hpp"
#include "trivar/am/trimmed_layer_slicer.hpp"
#include "trivar/core/parallel.hpp"

namespace trivar::am {

namespace {

// All layers of one slicer kind (LayerSlicer, or TrimmedLayerSlicer for trimmed cells).
template <class Slicer>
SliceSummary slice_layers(const Slicer& slicer, const SliceOptions& options, const LayerConsumer& consume,
                          const SliceProgress& progress, std::chrono::steady_clock::time_point start) {
  const SliceGrid& g = slicer.grid();
  const int n = g.layers;
  LayerStats total;
  int done = 0;
  std::mutex lock;
  std::exception_ptr failure;
  // Dynamic scheduling balances cheap polar layers against full equator layers; it cannot change a result.
#pragma omp parallel num_threads(resolve_threads(options.threads))
  {
    // Each thread slices into one layer, whose images a LayerSlicer clears where it wrote them and reuses
    // (unless the consumer moved them out).
    SliceLayer layer;
#pragma omp for schedule(dynamic, 1)
    for (int k = 0; k < n; ++k) {
      {
        std::lock_guard<std::mutex> guard(lock);
        if (failure) continue;
      }
      try {
        if constexpr (requires { slicer.slice(k, layer); })
          slicer.slice(k, layer);
        else
          layer = slicer.slice(k);
        const LayerStats stats = layer.stats;
        if (consume) consume(layer);
        std::lock_guard<std::mutex> guard(lock);
        total.merge(stats);
        ++done;
        if (progress) progress(done, n);
      } catch (...) {
        std::lock_guard<std::mutex> guard(lock);
        if (!failure) failure = std::current_exception();
      }
    }
  }
  if (failure) std::rethrow_exception(failure);
  SliceSummary s;
  s.layers = n;
  s.width = g.width;
  s.height = g.height;
  s.pixels = static_cast<std::int64_t>(n) * g.pixels();
  s.inside_pixels = total.inside_pixels;
  s.full_solves = total.full_solves;
  s.corrected_pixels = total.corrected_pixels;
  s.max_residual = total.max_residual;
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return s;
}

}  // namespace

SliceSummary slice_model(const VModel& model, const SliceOptions& options, const LayerConsumer& consume,
                         const SliceProgress& progress) {
  const auto start = std::chrono::steady_clock::now();
  for (const VCell& c : model.cells())
    if (c.is_trimmed()) return slice_layers(TrimmedLayerSlicer(model, options), options, consume, progress, start);
  return slice_layers(LayerSlicer(model, options), options, consume, progress, start);
}

std::vector<SliceLayer> slice_model(const VModel& model, const SliceOptions& options, SliceSummary* summary) {
  std::vector<SliceLayer> layers(static_cast<std::size_t>(slice_grid(model, options).layers));
  const SliceSummary s =
      slice_model(model, options, [&](SliceLayer& l) { layers[static_cast<std::size_t>(l.index)] = std::move(l); });
  if (summary) *summary = s;
  return layers;
}

std::string format_summary(const SliceSummary& s) {
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "layers %d, pixels %lld, inside pixels %lld, full-solve %.4g %%, max residual %.3g, seconds %.3f, "
                "inside pixels/s %.4g",
                s.layers, static_cast<long long>(s.pixels), static_cast<long long>(s.inside_pixels),
                s.full_solve_percent(), s.max_residual, s.seconds, s.inside_pixels_per_second());
  return buf;
}

}  // namespace trivar::am
