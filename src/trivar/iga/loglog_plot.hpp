#pragma once
// A minimal log-log line plot rendered to PNG (no text: axes, decade grid lines, polylines with markers), for
// convergence figures without a plotting dependency.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace trivar {

struct PlotSeries {
  std::vector<double> x, y;  // positive values; others are skipped
  std::array<std::uint8_t, 3> rgb{0, 0, 0};
};

// Throws trivar::Error when no series has a positive point or the file cannot be written.
void write_loglog_plot(const std::string& path, const std::vector<PlotSeries>& series, int width = 640,
                       int height = 480);

}  // namespace trivar
