#pragma once
// The pictures a terrain user looks at before reading numbers: the fitted height field coloured by height
// (a terrain colour ramp, hill-shaded from the north-west) and the error at the data points (white at 0, through
// yellow to red at the tolerance, purple above it, grey where no point lies; the largest error over bins of about
// four points, so scattered data shows as areas). RGB LayerImages, row 0 the
// lowest y (layer_image.hpp), so io::write_png shows north up. The pixel grid covers the spline's domain with
// square pixels, `width` across.
#include <cstdint>
#include <span>

#include "trivar/core/layer_image.hpp"
#include "trivar/fit/scattered_data.hpp"
#include "trivar/lr/lr_spline.hpp"

namespace trivar {

// `height`: an LR surface whose last control component is the height (dim 1, or a graph (x, y, z)).
// Throws trivar::Error for width outside 1..16384.
LayerImage<std::uint8_t> height_image(const LRSpline<2>& height, int width, int threads = 0);

// errors[i] belongs to data point i (errors.size() == data.size()); the image covers the points' bounding box.
LayerImage<std::uint8_t> error_image(const ScatteredData<2>& data, std::span<const double> errors, double tolerance,
                                     int width);

}  // namespace trivar
