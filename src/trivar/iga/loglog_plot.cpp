#include "trivar/iga/loglog_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "trivar/core/error.hpp"
#include "trivar/io/bitmap_font.hpp"
#include "trivar/io/png_writer.hpp"

namespace trivar {

namespace {

using Image = LayerImage<std::uint8_t>;
using io::Rgb;

constexpr Rgb background{255, 255, 255}, grid{220, 220, 220}, ink{0, 0, 0};
// Text at twice the font's size (10 x 14 pixel characters) reads comfortably on the default 640 x 480 figure.
constexpr int text_scale = 2, text_height = io::glyph_height * text_scale;
constexpr int pad = 10, gap = 6, tick = 5;  // border, text spacing and tick mark length, pixels

bool plotted(double x, double y) { return x > 0 && y > 0 && std::isfinite(x) && std::isfinite(y); }

// Bresenham, thickened to a 2 x 2 pen.
void line(Image& img, int x0, int y0, int x1, int y1, const Rgb& c) {
  const int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0);
  const int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
  int err = dx + dy;
  while (true) {
    io::fill_rect(img, x0, y0, 2, 2, c);
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

void marker(Image& img, int x, int y, const Rgb& c) { io::fill_rect(img, x - 3, y - 3, 7, 7, c); }

// 10^k set as in print: "10" and the exponent raised in the font's own size, so labels stay short and need
// no notation to decode.
constexpr int exponent_rise = 10;  // bottom of the exponent above the bottom of "10"
constexpr int decade_label_height = exponent_rise + io::glyph_height;

int decade_label_width(int k) { return io::text_width("10", text_scale) + io::text_width(std::to_string(k)); }

void draw_decade_label(Image& img, int x, int y, int k) {
  io::draw_text(img, x, y, "10", ink, text_scale);
  io::draw_text(img, x + io::text_width("10", text_scale), y + exponent_rise, std::to_string(k), ink);
}

// Every stride-th decade is labelled, so that neighbouring labels of `extent` pixels keep a gap between them.
int label_stride(double decade_pixels, int extent) {
  return std::max(1, static_cast<int>(std::ceil((extent + gap) / decade_pixels)));
}

// Pixels of [x, x + w) x [y, y + h) that the series have drawn (neither background nor grid).
int series_pixels(const Image& img, int x, int y, int w, int h) {
  int n = 0;
  for (int py = std::max(y, 0); py < std::min(y + h, img.height()); ++py)
    for (int px = std::max(x, 0); px < std::min(x + w, img.width()); ++px) {
      const std::uint8_t* p = img.pixel(px, py);
      const Rgb c{p[0], p[1], p[2]};
      n += c != background && c != grid;
    }
  return n;
}

// A framed box of one row per entry (a stretch of line with a marker, then the label), drawn over the series
// in the corner of the plot box [x0, x1] x [y0, y1] where it hides the fewest series pixels. Convergence curves
// fall to the right, so the top right is tried first and wins ties.
void draw_legend(Image& img, const std::vector<const PlotSeries*>& entries, int x0, int y0, int x1, int y1) {
  constexpr int inner = 6, swatch = 24, row_gap = 6, inset = 8;
  int label_width = 0;
  for (const auto* s : entries) label_width = std::max(label_width, io::text_width(s->label, text_scale));
  const int n = static_cast<int>(entries.size());
  const int w = 2 * inner + swatch + gap + label_width, h = 2 * inner + n * text_height + (n - 1) * row_gap;
  const std::array<std::array<int, 2>, 4> corners{{{x1 - inset - w, y1 - inset - h},
                                                   {x0 + inset, y0 + inset},
                                                   {x0 + inset, y1 - inset - h},
                                                   {x1 - inset - w, y0 + inset}}};
  auto best = corners[0];
  int least = std::numeric_limits<int>::max();
  for (const auto& c : corners)
    if (const int hidden = series_pixels(img, c[0], c[1], w, h); hidden < least) {
      least = hidden;
      best = c;
    }
  const int lx = best[0], ly = best[1];
  io::fill_rect(img, lx, ly, w, h, ink);
  io::fill_rect(img, lx + 1, ly + 1, w - 2, h - 2, background);
  for (int j = 0; j < n; ++j) {
    const PlotSeries& s = *entries[static_cast<std::size_t>(j)];
    const int ty = ly + h - inner - (j + 1) * text_height - j * row_gap, mid = ty + text_height / 2 - 1;
    line(img, lx + inner, mid, lx + inner + swatch, mid, s.rgb);
    marker(img, lx + inner + swatch / 2, mid, s.rgb);
    io::draw_text(img, lx + inner + swatch + gap, ty, s.label, ink, text_scale);
  }
}

}  // namespace

void write_loglog_plot(const std::string& path, const std::vector<PlotSeries>& series, const PlotOptions& options) {
  double lo[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  double hi[2] = {-lo[0], -lo[1]};
  for (const auto& s : series)
    for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i)
      if (plotted(s.x[i], s.y[i])) {
        lo[0] = std::min(lo[0], std::log10(s.x[i]));
        hi[0] = std::max(hi[0], std::log10(s.x[i]));
        lo[1] = std::min(lo[1], std::log10(s.y[i]));
        hi[1] = std::max(hi[1], std::log10(s.y[i]));
      }
  require(lo[0] <= hi[0], "plot: no positive data to plot in " + path);
  // Whole decades on both axes, so the grid lines and the tick labels mark powers of ten.
  int first[2], last[2];
  for (int a = 0; a < 2; ++a) {
    first[a] = static_cast<int>(std::floor(lo[a]));
    last[a] = std::max(static_cast<int>(std::ceil(hi[a])), first[a] + 1);
  }
  int widest[2] = {0, 0};
  for (int a = 0; a < 2; ++a)
    for (int k = first[a]; k <= last[a]; ++k) widest[a] = std::max(widest[a], decade_label_width(k));

  // Margins hold, from the border inwards: the axis label, the tick labels and the tick marks. The outermost
  // tick labels are centred on the plot box's corners and overhang it by half their size.
  const int label_band = text_height + gap;
  const int left = pad + (options.y_label.empty() ? 0 : label_band) + widest[1] + gap + tick;
  const int bottom = pad + (options.x_label.empty() ? 0 : label_band) + decade_label_height + gap + tick;
  const int right = options.width - pad - widest[0] / 2;
  const int top = options.height - pad - (options.title.empty() ? 0 : label_band) - decade_label_height / 2;
  require(right > left && top > bottom, [&] {
    return "plot: " + std::to_string(options.width) + " x " + std::to_string(options.height) +
           " pixels leave no room for the plot box beside the labels (" + path + ")";
  });

  Image img(options.width, options.height, 3, 255);
  auto px = [&](double x) {
    return left + static_cast<int>(std::lround((std::log10(x) - first[0]) / (last[0] - first[0]) * (right - left)));
  };
  auto py = [&](double y) {
    return bottom + static_cast<int>(std::lround((std::log10(y) - first[1]) / (last[1] - first[1]) * (top - bottom)));
  };
  for (int k = first[0]; k <= last[0]; ++k)
    io::fill_rect(img, px(std::pow(10.0, k)), bottom, 1, top - bottom + 1, grid);
  for (int k = first[1]; k <= last[1]; ++k)
    io::fill_rect(img, left, py(std::pow(10.0, k)), right - left + 1, 1, grid);

  std::vector<const PlotSeries*> legend;
  for (const auto& s : series) {
    int prev_x = -1, prev_y = -1;
    for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!plotted(s.x[i], s.y[i])) continue;
      const int x = px(s.x[i]), y = py(s.y[i]);
      if (prev_x >= 0) line(img, prev_x, prev_y, x, y, s.rgb);
      marker(img, x, y, s.rgb);
      prev_x = x;
      prev_y = y;
    }
    if (!s.label.empty() && prev_x >= 0) legend.push_back(&s);
  }

  // Axes and ticks go over the series, so markers on the edges of the box do not hide them.
  io::fill_rect(img, left, bottom, right - left + 2, 2, ink);
  io::fill_rect(img, left, bottom, 2, top - bottom + 2, ink);
  const int stride_x = label_stride(static_cast<double>(right - left) / (last[0] - first[0]), widest[0]);
  const int stride_y = label_stride(static_cast<double>(top - bottom) / (last[1] - first[1]), decade_label_height);
  for (int k = first[0]; k <= last[0]; ++k) {
    const int x = px(std::pow(10.0, k));
    io::fill_rect(img, x, bottom - tick, 2, tick, ink);
    if ((k - first[0]) % stride_x == 0)
      draw_decade_label(img, x - decade_label_width(k) / 2, bottom - tick - gap - decade_label_height, k);
  }
  for (int k = first[1]; k <= last[1]; ++k) {
    const int y = py(std::pow(10.0, k));
    io::fill_rect(img, left - tick, y, tick, 2, ink);
    if ((k - first[1]) % stride_y == 0)
      draw_decade_label(img, left - tick - gap - decade_label_width(k), y - decade_label_height / 2, k);
  }
  io::draw_text(img, (left + right - io::text_width(options.x_label, text_scale)) / 2, pad, options.x_label, ink,
                text_scale);
  io::draw_text(img, pad, (bottom + top - io::text_width(options.y_label, text_scale)) / 2, options.y_label, ink,
                text_scale, io::TextDirection::up);
  io::draw_text(img, (left + right - io::text_width(options.title, text_scale)) / 2,
                options.height - pad - text_height, options.title, ink, text_scale);
  if (!legend.empty()) draw_legend(img, legend, left, bottom, right, top);
  io::write_png(path, img);
}

}  // namespace trivar
