#pragma once
// LayerImage<T>: a width x height raster of one printed layer with `channels` values per pixel, row-major
// with x fastest. Row 0 is the LOWEST y of the build plate (y up, the slicer's scanline order); writers that
// store top-down formats (PNG) flip the rows so the picture shows the layer as seen from above, +y pointing up.
//
// Two uses carry the material pipeline:
//   FractionImage (float, channels = number of materials): desired material fractions per pixel; a pixel whose
//     fractions are all <= 0 lies outside the part.
//   LabelImage (uint8, one channel): the material of each pixel after dithering, 0 = empty (outside the part),
//     k + 1 = material k of the MaterialTable. The label is the palette index of a palette PNG.
// 8-bit grey (1 channel), RGB (3) and RGBA (4) LayerImage<uint8_t> serve previews.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "trivar/core/error.hpp"

namespace trivar {

template <class T>
class LayerImage {
public:
  LayerImage() = default;
  LayerImage(int width, int height, int channels = 1, T fill = T{}) : width_(width), height_(height), channels_(channels) {
    require(width >= 0 && height >= 0 && channels >= 1,
            "LayerImage: bad size " + std::to_string(width) + " x " + std::to_string(height) + " x " +
                std::to_string(channels));
    data_.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * static_cast<std::size_t>(channels),
                 fill);
  }

  int width() const { return width_; }
  int height() const { return height_; }
  int channels() const { return channels_; }
  std::size_t pixel_count() const { return static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_); }

  // The `channels` values of pixel (x, y); no bounds check (hot path).
  T* pixel(int x, int y) { return data_.data() + offset(x, y); }
  const T* pixel(int x, int y) const { return data_.data() + offset(x, y); }
  T& operator()(int x, int y, int c = 0) { return data_[offset(x, y) + static_cast<std::size_t>(c)]; }
  const T& operator()(int x, int y, int c = 0) const { return data_[offset(x, y) + static_cast<std::size_t>(c)]; }

  std::vector<T>& data() { return data_; }
  const std::vector<T>& data() const { return data_; }

private:
  std::size_t offset(int x, int y) const {
    return (static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x)) *
           static_cast<std::size_t>(channels_);
  }

  int width_ = 0, height_ = 0, channels_ = 1;
  std::vector<T> data_;
};

using FractionImage = LayerImage<float>;
using LabelImage = LayerImage<std::uint8_t>;

// Label of an empty (outside) pixel; material k has label k + 1.
inline constexpr std::uint8_t empty_label = 0;

}  // namespace trivar
