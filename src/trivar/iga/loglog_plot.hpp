#pragma once
// A log-log line plot written as SVG (text is the viewer's, so no font is needed): decade grid lines, axes
// with a tick and the power of ten at every decade, axis labels, an optional title, and polylines with
// markers named in a legend. Each series is a <g> whose <title> is its label, holding its <polyline> (and a
// <circle> per point), so the data can be read back from the file.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace trivar {

struct PlotSeries {
  std::vector<double> x, y;  // pairs of positive finite values are plotted; others are skipped
  std::array<std::uint8_t, 3> rgb{0, 0, 0};
  std::string label{};  // legend entry; a series without a label or without a plotted point has none
};

struct PlotOptions {
  std::string x_label{}, y_label{}, title{};  // each drawn only when non-empty
  int width = 640, height = 480;              // SVG user units (pixels at 100 %)
};

// Throws trivar::Error when no series has a plotted point, the size leaves no room for the plot box beside
// the labels, or the file cannot be written (nothing is written then).
void write_loglog_plot(const std::string& path, const std::vector<PlotSeries>& series,
                       const PlotOptions& options = {});

}  // namespace trivar
