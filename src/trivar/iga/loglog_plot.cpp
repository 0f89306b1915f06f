#include "trivar/iga/loglog_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "trivar/core/error.hpp"
#include "trivar/io/png_writer.hpp"

namespace trivar {

namespace {

using Image = am::LayerImage<std::uint8_t>;

void put(Image& img, int x, int y, const std::array<std::uint8_t, 3>& c) {
  if (x < 0 || y < 0 || x >= img.width() || y >= img.height()) return;
  std::uint8_t* p = img.pixel(x, y);
  p[0] = c[0];
  p[1] = c[1];
  p[2] = c[2];
}

// Bresenham, thickened to a 2 x 2 pen.
void line(Image& img, int x0, int y0, int x1, int y1, const std::array<std::uint8_t, 3>& c) {
  const int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0);
  const int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
  int err = dx + dy;
  while (true) {
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) put(img, x0 + a, y0 + b, c);
    if (x0 == x1 && y0 == y1) break;
    const int e2 = 2 * err;
    if (e2 >= dy) {
      err += dy;
      x0 += sx;
    }
    if (e2 <= dx) {
      err += dx;
      y0 += sy;
    }
  }
}

}  // namespace

void write_loglog_plot(const std::string& path, const std::vector<PlotSeries>& series, int width, int height) {
  double lo[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  double hi[2] = {-lo[0], -lo[1]};
  for (const auto& s : series)
    for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i)
      if (s.x[i] > 0 && s.y[i] > 0) {
        lo[0] = std::min(lo[0], std::log10(s.x[i]));
        hi[0] = std::max(hi[0], std::log10(s.x[i]));
        lo[1] = std::min(lo[1], std::log10(s.y[i]));
        hi[1] = std::max(hi[1], std::log10(s.y[i]));
      }
  require(lo[0] <= hi[0], "plot: no positive data to plot in " + path);
  // Whole decades on both axes, so the grid lines mark powers of ten.
  for (int a = 0; a < 2; ++a) {
    lo[a] = std::floor(lo[a]);
    hi[a] = std::max(std::ceil(hi[a]), lo[a] + 1);
  }
  const int margin = 30;
  Image img(width, height, 3, 255);
  auto px = [&](double x) { return margin + static_cast<int>(std::lround((std::log10(x) - lo[0]) / (hi[0] - lo[0]) * (width - 2 * margin))); };
  auto py = [&](double y) { return margin + static_cast<int>(std::lround((std::log10(y) - lo[1]) / (hi[1] - lo[1]) * (height - 2 * margin))); };
  const std::array<std::uint8_t, 3> grid{220, 220, 220}, axis{0, 0, 0};
  for (double d = lo[0]; d <= hi[0]; d += 1) {
    const int x = px(std::pow(10.0, d));
    for (int y = margin; y <= height - margin; ++y) put(img, x, y, grid);
  }
  for (double d = lo[1]; d <= hi[1]; d += 1) {
    const int y = py(std::pow(10.0, d));
    for (int x = margin; x <= width - margin; ++x) put(img, x, y, grid);
  }
  line(img, margin, margin, width - margin, margin, axis);
  line(img, margin, margin, margin, height - margin, axis);
  for (const auto& s : series) {
    int prev_x = -1, prev_y = -1;
    for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!(s.x[i] > 0 && s.y[i] > 0)) continue;
      const int x = px(s.x[i]), y = py(s.y[i]);
      if (prev_x >= 0) line(img, prev_x, prev_y, x, y, s.rgb);
      for (int a = -3; a <= 3; ++a)
        for (int b = -3; b <= 3; ++b) put(img, x + a, y + b, s.rgb);
      prev_x = x;
      prev_y = y;
    }
  }
  io::write_png(path, img);
}

}  // namespace trivar
