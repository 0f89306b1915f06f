#pragma once
// One sliced layer: which cell every pixel belongs to and the material fractions there, plus the statistics
// of the point inversions that produced it. The raster follows slice_options.hpp (row 0 at the lowest y).
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "trivar/core/layer_image.hpp"

namespace trivar::am {

struct LayerStats {
  std::int64_t inside_pixels = 0;
  // Robust point inversions (subdivision search): tracing from the neighbours failed or had no neighbour of
  // the same cell to start from. Includes the searches in other cells for pixels whose cell was corrected.
  std::int64_t full_solves = 0;
  // Pixels whose owner was not the first cell claiming them by its outline (a chord of a shared face
  // claimed a centre of the neighbour, or no fill claimed a centre inside the part); see layer_slicer.hpp.
  std::int64_t corrected_pixels = 0;
  // Largest |x(u, v, w) - pixel centre| over the inside pixels (model units).
  double max_residual = 0;

  void merge(const LayerStats& o) {
    inside_pixels += o.inside_pixels;
    full_solves += o.full_solves;
    corrected_pixels += o.corrected_pixels;
    max_residual = std::max(max_residual, o.max_residual);
  }
};

struct SliceLayer {
  int index = 0;  // layer number k
  double z = 0;   // sampling height z_k
  int width = 0, height = 0;
  // Cell index per pixel (x fastest, row 0 at the lowest y), -1 outside the part.
  std::vector<int> cell;
  // Material fractions per pixel (channels = materials), clamped to [0, 1] and summing to 1 inside; all 0
  // outside, which is what am::dither() reads as empty.
  FractionImage fractions;
  // Per row, the columns [begin, end) the slicer may have written: every pixel outside is -1 with fractions 0.
  // Empty when the slicer does not record them. A layer handed back to LayerSlicer::slice(k, layer) is cleared
  // within these extents only, instead of being filled whole.
  std::vector<std::array<int, 2>> row_extents;
  LayerStats stats;

  int owner(int i, int j) const { return cell[static_cast<std::size_t>(j) * static_cast<std::size_t>(width) + i]; }
};

}  // namespace trivar::am
