#pragma once
// A log-log figure read back for the plot tests: the axes and the decade lines are found in the PNG itself, so
// the tests check the drawing without restating its layout constants.
#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "support/png_reader.hpp"

namespace iga_test {

using Rgb = std::array<std::uint8_t, 3>;
inline constexpr Rgb black{0, 0, 0}, grid{220, 220, 220};

struct Figure {
  trivar::test::PngFile png;
  int width = 0, height = 0;
  // PNG pixels (row 0 at the top). The axes are the plot box's left and bottom edges; the first decade of each
  // axis lies on the other axis, the last on the opposite edge of the box.
  int axis_col = -1, axis_row = -1;
  std::vector<int> x_decades{};  // columns, left to right
  std::vector<int> y_decades{};  // rows, bottom to top

  int right() const { return x_decades.back(); }
  int top() const { return y_decades.back(); }

  // Pixels of colour `c` in columns [c0, c1) and rows [r0, r1), clipped to the image.
  int count(const Rgb& c, int c0, int c1, int r0, int r1) const {
    int n = 0;
    for (int r = std::max(r0, 0); r < std::min(r1, height); ++r)
      for (int x = std::max(c0, 0); x < std::min(c1, width); ++x) n += png.rgb(x, r) == c;
    return n;
  }
  // As count, over the fractions [fx0, fx1] of the plot box's width (from the left) and [fy0, fy1] of its height
  // (from the bottom).
  int count_in_box(const Rgb& c, double fx0, double fx1, double fy0, double fy1) const {
    auto col = [&](double f) { return axis_col + static_cast<int>(f * (right() - axis_col)); };
    auto row = [&](double f) { return axis_row - static_cast<int>(f * (axis_row - top())); };
    return count(c, col(fx0), col(fx1) + 1, row(fy1), row(fy0) + 1);
  }
};

// Longest run of `c` along a column (vertical) or a row.
inline int longest_run(const Figure& f, const Rgb& c, int line, bool vertical) {
  int best = 0, run = 0;
  for (int i = 0; i < (vertical ? f.height : f.width); ++i) {
    run = (vertical ? f.png.rgb(line, i) : f.png.rgb(i, line)) == c ? run + 1 : 0;
    best = std::max(best, run);
  }
  return best;
}

inline Figure read_figure(const std::string& path) {
  Figure f{trivar::test::read_png(path)};
  f.width = static_cast<int>(f.png.width);
  f.height = static_cast<int>(f.png.height);
  // The axes are the longest black lines, two pixels thick: the leftmost column and the lowest row of each.
  int longest_col = 0, longest_row = 0;
  for (int x = 0; x < f.width; ++x) longest_col = std::max(longest_col, longest_run(f, black, x, true));
  for (int r = 0; r < f.height; ++r) longest_row = std::max(longest_row, longest_run(f, black, r, false));
  for (int x = f.width - 1; x >= 0; --x)
    if (longest_run(f, black, x, true) == longest_col) f.axis_col = x;
  for (int r = 0; r < f.height; ++r)
    if (longest_run(f, black, r, false) == longest_row) f.axis_row = r;
  // The first decade line of each axis is hidden under the other axis; the rest are grid lines across most of
  // the box (series and the legend cover parts of them).
  f.x_decades.push_back(f.axis_col);
  for (int x = f.axis_col + 2; x < f.width; ++x)
    if (f.count(grid, x, x + 1, 0, f.axis_row) > 4 * f.axis_row / 10) f.x_decades.push_back(x);
  f.y_decades.push_back(f.axis_row);
  for (int r = f.axis_row - 2; r >= 0; --r)
    if (f.count(grid, f.axis_col + 2, f.width, r, r + 1) > 4 * (f.width - f.axis_col) / 10) f.y_decades.push_back(r);
  return f;
}

}  // namespace iga_test
