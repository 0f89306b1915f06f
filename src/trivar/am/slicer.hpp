#pragma once
// Slicing a whole model: every layer of the grid (slice_options.hpp) by LayerSlicer, in parallel over layers,
// with progress reporting and summary statistics. Each layer is computed by the same code from the same
// inputs whatever thread runs it (tracing state never crosses layers), so the layers are bit-identical for
// any thread count.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "trivar/am/slice_layer.hpp"
#include "trivar/am/slice_options.hpp"
#include "trivar/model/vmodel.hpp"

namespace trivar::am {

struct SliceSummary {
  int layers = 0;
  int width = 0, height = 0;
  std::int64_t pixels = 0;  // layers * width * height
  std::int64_t inside_pixels = 0;
  std::int64_t full_solves = 0;
  std::int64_t corrected_pixels = 0;
  double max_residual = 0;
  double seconds = 0;  // wall-clock time of the whole slicing, consumer included

  // Robust solves per inside pixel, in percent (the reference reached 0.0044 %).
  double full_solve_percent() const { return inside_pixels > 0 ? 100.0 * double(full_solves) / double(inside_pixels) : 0.0; }
  double inside_pixels_per_second() const { return seconds > 0 ? double(inside_pixels) / seconds : 0.0; }
};

// Receives each finished layer exactly once, in any order and possibly from several threads at once (a
// consumer that writes one file per layer needs no locking); it may move the layer's data out, but must not
// otherwise change its pixels: the thread slices its next layer into the same images (LayerSlicer::slice).
using LayerConsumer = std::function<void(SliceLayer& layer)>;
// Called after each layer is consumed with the count of finished layers (1..total, increasing), serialised
// by a lock so it may draw a progress bar.
using SliceProgress = std::function<void(int done, int total)>;

// Slices every layer and returns the statistics. The first exception thrown by a layer or the consumer
// stops the remaining layers and is rethrown. Throws trivar::Error for invalid options (see LayerSlicer).
SliceSummary slice_model(const VModel& model, const SliceOptions& options, const LayerConsumer& consume,
                         const SliceProgress& progress = {});

// All layers in memory, in layer order (for small jobs and tests), and the statistics.
std::vector<SliceLayer> slice_model(const VModel& model, const SliceOptions& options, SliceSummary* summary = nullptr);

// One line: "layers N, pixels N, inside pixels N, full-solve X %, max residual R, seconds S,
// inside pixels/s V".
std::string format_summary(const SliceSummary& s);

}  // namespace trivar::am
