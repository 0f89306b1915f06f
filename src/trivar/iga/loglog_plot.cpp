#include "trivar/iga/loglog_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <ostream>

#include "trivar/core/atomic_file.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/xml_text.hpp"

namespace trivar {

namespace {

// Room for the text, in user units: the viewer's 14-unit sans-serif font needs about 8 units per character.
constexpr int kFont = 14, kPad = 10, kTick = 5, kGap = 6;
constexpr int kLeft = kPad + kFont + kGap + 6 * 8 + kGap + kTick;   // y label, tick labels like "10-12"
constexpr int kBottom = kPad + kFont + kGap + kFont + kGap + kTick;  // x label, tick labels
constexpr int kRight = kPad + 3 * 8;                                 // half of the last x tick label
constexpr int kTop = kPad + kFont / 2;                               // half of the top y tick label

bool plotted(double x, double y) { return x > 0 && y > 0 && std::isfinite(x) && std::isfinite(y); }

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

std::string colour(const std::array<std::uint8_t, 3>& c) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", c[0], c[1], c[2]);
  return buf;
}

// 10^k as "10" with the exponent raised, so labels stay short and need no notation to decode.
void decade_label(std::ostream& os, double x, double y, const char* anchor, int k) {
  os << "<text x=\"" << num(x) << "\" y=\"" << num(y) << "\" text-anchor=\"" << anchor << "\">10<tspan dy=\"-6\" "
     << "font-size=\"" << kFont * 3 / 4 << "\">" << k << "</tspan></text>\n";
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
  const int W = options.width, H = options.height;
  const double left = kLeft, right = W - kRight;
  const double bottom = H - kBottom, top = kTop + (options.title.empty() ? 0 : kFont + kGap);
  require(right - left >= 50 && bottom - top >= 50, [&] {
    return "plot: " + std::to_string(W) + " x " + std::to_string(H) +
           " leaves no room for the plot box beside the labels (" + path + ")";
  });
  auto px = [&](double x) { return left + (std::log10(x) - first[0]) / (last[0] - first[0]) * (right - left); };
  auto py = [&](double y) { return bottom - (std::log10(y) - first[1]) / (last[1] - first[1]) * (bottom - top); };
  // Every stride-th decade is labelled, so that neighbouring labels keep a gap between them.
  const int stride_x = std::max(1, static_cast<int>(std::ceil(6 * 8 / ((right - left) / (last[0] - first[0])))));
  const int stride_y = std::max(1, static_cast<int>(std::ceil(2 * kFont / ((bottom - top) / (last[1] - first[1])))));

  write_file_atomically(path, [&](std::ostream& os) {
    os << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
       << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H << "\" viewBox=\"0 0 " << W
       << ' ' << H << "\" font-family=\"sans-serif\" font-size=\"" << kFont << "\">\n"
       << "<rect width=\"" << W << "\" height=\"" << H << "\" fill=\"white\"/>\n";
    os << "<g class=\"grid\" stroke=\"#dcdcdc\">\n";
    for (int k = first[0]; k <= last[0]; ++k) {
      const double x = px(std::pow(10.0, k));
      os << "<line x1=\"" << num(x) << "\" y1=\"" << num(top) << "\" x2=\"" << num(x) << "\" y2=\"" << num(bottom)
         << "\"/>\n";
    }
    for (int k = first[1]; k <= last[1]; ++k) {
      const double y = py(std::pow(10.0, k));
      os << "<line x1=\"" << num(left) << "\" y1=\"" << num(y) << "\" x2=\"" << num(right) << "\" y2=\"" << num(y)
         << "\"/>\n";
    }
    os << "</g>\n";

    std::vector<const PlotSeries*> legend;
    for (const auto& s : series) {
      std::string points;
      for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i)
        if (plotted(s.x[i], s.y[i])) {
          if (!points.empty()) points += ' ';
          points += num(px(s.x[i]));
          points += ',';
          points += num(py(s.y[i]));
        }
      if (points.empty()) continue;
      const std::string c = colour(s.rgb);
      os << "<g class=\"series\" stroke=\"" << c << "\" fill=\"" << c << "\"><title>" << io::xml_escape(s.label)
         << "</title>\n<polyline fill=\"none\" stroke-width=\"2\" points=\"" << points << "\"/>\n";
      for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i)
        if (plotted(s.x[i], s.y[i]))
          os << "<circle cx=\"" << num(px(s.x[i])) << "\" cy=\"" << num(py(s.y[i])) << "\" r=\"3.5\"/>\n";
      os << "</g>\n";
      if (!s.label.empty()) legend.push_back(&s);
    }

    // Axes and ticks over the series, so markers on the edges of the box do not hide them.
    os << "<g class=\"axes\" stroke=\"black\" stroke-width=\"1.5\" fill=\"none\">\n<polyline points=\"" << num(left)
       << ',' << num(top) << ' ' << num(left) << ',' << num(bottom) << ' ' << num(right) << ',' << num(bottom)
       << "\"/>\n</g>\n<g class=\"x-ticks\">\n";
    for (int k = first[0]; k <= last[0]; ++k) {
      const double x = px(std::pow(10.0, k));
      os << "<line x1=\"" << num(x) << "\" y1=\"" << num(bottom) << "\" x2=\"" << num(x) << "\" y2=\""
         << num(bottom + kTick) << "\" stroke=\"black\"/>\n";
      if ((k - first[0]) % stride_x == 0) decade_label(os, x, bottom + kTick + kGap + kFont, "middle", k);
    }
    os << "</g>\n<g class=\"y-ticks\">\n";
    for (int k = first[1]; k <= last[1]; ++k) {
      const double y = py(std::pow(10.0, k));
      os << "<line x1=\"" << num(left - kTick) << "\" y1=\"" << num(y) << "\" x2=\"" << num(left) << "\" y2=\""
         << num(y) << "\" stroke=\"black\"/>\n";
      if ((k - first[1]) % stride_y == 0) decade_label(os, left - kTick - kGap, y + kFont / 3.0, "end", k);
    }
    os << "</g>\n";
    if (!options.x_label.empty())
      os << "<text class=\"x-label\" x=\"" << num((left + right) / 2) << "\" y=\"" << H - kPad
         << "\" text-anchor=\"middle\">" << io::xml_escape(options.x_label) << "</text>\n";
    if (!options.y_label.empty())
      os << "<text class=\"y-label\" transform=\"translate(" << kPad + kFont << ',' << num((top + bottom) / 2)
         << ") rotate(-90)\" text-anchor=\"middle\">" << io::xml_escape(options.y_label) << "</text>\n";
    if (!options.title.empty())
      os << "<text class=\"title\" x=\"" << num((left + right) / 2) << "\" y=\"" << kPad + kFont
         << "\" text-anchor=\"middle\">" << io::xml_escape(options.title) << "</text>\n";
    if (!legend.empty()) {
      // Top right: convergence curves fall to the right, so that corner is the emptiest.
      const double w = 150, h = 8 + 20.0 * static_cast<double>(legend.size()), x0 = right - w - 8, y0 = top + 8;
      os << "<g class=\"legend\">\n<rect x=\"" << num(x0) << "\" y=\"" << num(y0) << "\" width=\"" << num(w)
         << "\" height=\"" << num(h) << "\" fill=\"white\" stroke=\"black\"/>\n";
      for (std::size_t j = 0; j < legend.size(); ++j) {
        const double y = y0 + 14 + 20.0 * static_cast<double>(j);
        const std::string c = colour(legend[j]->rgb);
        os << "<line x1=\"" << num(x0 + 8) << "\" y1=\"" << num(y) << "\" x2=\"" << num(x0 + 32) << "\" y2=\""
           << num(y) << "\" stroke=\"" << c << "\" stroke-width=\"2\"/>\n<circle cx=\"" << num(x0 + 20) << "\" cy=\""
           << num(y) << "\" r=\"3.5\" fill=\"" << c << "\"/>\n<text x=\"" << num(x0 + 40) << "\" y=\""
           << num(y + kFont / 3.0) << "\">" << io::xml_escape(legend[j]->label) << "</text>\n";
      }
      os << "</g>\n";
    }
    os << "</svg>\n";
  });
}

}  // namespace trivar
