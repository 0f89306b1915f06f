#pragma once
// Parameters of the graded-material slicer (model units, mm) and the raster they resolve to.
//
// Sampling convention (used by every part of the slicer and by the tests):
//   layer k (0-based) is sampled at  z_k = z0 + (k + 0.5) * layer_thickness,
//   pixel (i, j) of a layer has its centre at  x_i = x0 + (i + 0.5) * dx,  y_j = y0 + (j + 0.5) * dy,
// with dx = 25.4 / dpi_x and dy = 25.4 / dpi_y (mm), i the column (x fastest in memory) and j the row, row 0
// at the LOWEST y (the convention of LayerImage). A pixel is inside the part when its centre is.
#include <array>
#include <cmath>
#include <optional>
#include <string>

#include "trivar/spline/point_inversion.hpp"

namespace trivar::am {

// Where Newton's method starts the point inversion of a pixel centre (the methods compared in seed 001).
enum class Tracing {
  none,            // the robust subdivision search for every pixel
  previous_point,  // from the pixels to the left in the same cell (extrapolated), else the robust search
  previous_line,   // from the pixel below or the nearest one of the cell on the previous row, else robust
  full,            // previous point, else the cell's outline crossing where the row enters, else previous line
};

struct SliceOptions {
  double layer_thickness = 0.027;  // mm
  double dpi_x = 600, dpi_y = 600;  // printer resolution per direction, e.g. 600 x 300
  // Build-plate position (x0, y0) of the image's lower-left corner. Default: the model's bounding box minus
  // one pixel, so the part never touches the image border.
  std::optional<std::array<double, 2>> origin;
  // Image size (width, height) in pixels. Default: up to the bounding box's upper corner plus one pixel.
  std::optional<std::array<int, 2>> image_size;
  // Sliced height range [z0, z1]. Default: the bounding box's z extent. Layers: ceil((z1 - z0) / thickness).
  std::optional<std::array<double, 2>> z_range;
  // Cell attribute giving the material fractions. Unset: "material" when the cells have it, else the part is
  // one material (fraction 1). Set: every cell must have it. Either way all cells or none must have it.
  std::optional<std::string> material_attribute;
  int threads = 0;  // layers sliced in parallel; <= 0: all available
  // Outline polygons: largest distance of a chord from the true section curve, as a fraction of the smaller
  // pixel size. Their vertices lie on the curve to rounding, so only pixel centres closer than this to the
  // boundary may be misclassified.
  double outline_tolerance = 1e-3;
  // Marching grid on each cell face: samples per knot span and direction. Only the topology of the section
  // depends on it (a loop smaller than a grid quad may be missed); the accuracy is outline_tolerance's.
  int samples_per_span = 16;
  // Point inversion (x, y, z) -> (u, v, w) of the pixel centres. The tolerance (relative to each cell's
  // control-box diagonal) bounds |x(u, v, w) - centre|; tighter than InversionOptions' default because
  // tracing usually converges past it in the same number of Newton steps.
  InversionOptions inversion{.tolerance = 1e-9};
  Tracing tracing = Tracing::full;
};

// "none", "previous-point", "previous-line", "full"; parse_tracing throws trivar::Error for other names.
const char* to_string(Tracing t);
Tracing parse_tracing(const std::string& name);

// The options resolved against a model: the raster and the layers.
struct SliceGrid {
  double x0 = 0, y0 = 0, dx = 0, dy = 0;
  int width = 0, height = 0;
  double z0 = 0, thickness = 0;
  int layers = 0;

  double x(int i) const { return x0 + (i + 0.5) * dx; }
  double y(int j) const { return y0 + (j + 0.5) * dy; }
  double z(int k) const { return z0 + (k + 0.5) * thickness; }
  // Pixels per layer.
  long long pixels() const { return static_cast<long long>(width) * height; }
};

}  // namespace trivar::am
