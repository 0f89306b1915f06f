#pragma once
// fill_rect: the one drawing primitive of generated RGB figures; plot lines, markers, legends and bitmap text
// are all built from it. It clips to the image, so a drawing may overhang the border without checks at every
// call site.
#include <algorithm>
#include <array>
#include <cstdint>

#include "trivar/core/layer_image.hpp"
#include "trivar/core/error.hpp"

namespace trivar::io {

using Rgb = std::array<std::uint8_t, 3>;

// Paints the pixels [x, x + w) x [y, y + h) of an RGB image (3 channels) that lie inside it; throws
// trivar::Error for another channel count.
inline void fill_rect(LayerImage<std::uint8_t>& image, int x, int y, int w, int h, const Rgb& colour) {
  require(image.channels() == 3,
          [&] { return "fill_rect: image has " + std::to_string(image.channels()) + " channels, not RGB"; });
  const int x0 = std::max(x, 0), x1 = std::min(x + w, image.width());
  const int y0 = std::max(y, 0), y1 = std::min(y + h, image.height());
  for (int py = y0; py < y1; ++py)
    for (int px = x0; px < x1; ++px) std::copy(colour.begin(), colour.end(), image.pixel(px, py));
}

}  // namespace trivar::io
