// Log-log plot, read back from the PNG: a grid line, a tick mark and a tick label at every decade and no text
// between decades; axis labels and a title exactly when asked for, centred on the plot box; a legend of the
// labelled series with points, in a corner of the box that the data leave free.
#include <gtest/gtest.h>

#include <cstdlib>

#include "iga/plot_figure.hpp"
#include "support/temp_dir.hpp"
#include "trivar/core/error.hpp"
#include "trivar/iga/loglog_plot.hpp"

using namespace trivar;
using iga_test::black;
using iga_test::Figure;
using iga_test::read_figure;

namespace {

constexpr iga_test::Rgb blue{30, 80, 220}, red{220, 40, 40}, green{40, 150, 60};

// Over x = 10 .. 10^4 and y = 10^-7 .. 10^-1 both series fall below the line from the middle of the left edge
// to the middle of the bottom edge, so the box's top-right quarter holds no data. The third has no plotted point.
std::vector<PlotSeries> falling() {
  return {{{10, 100, 1000, 10000}, {1e-1, 1e-3, 1e-5, 1e-6}, blue, "first"},
          {{10, 100, 1000, 10000}, {1e-2, 1e-4, 1e-6, 1e-7}, red, "second"},
          {{10, 100}, {-1, 0}, green, "nothing"}};
}

Figure plot(const test::TempDir& dir, const std::vector<PlotSeries>& series, const PlotOptions& options = {}) {
  const std::string path = dir.file("plot.png");
  write_loglog_plot(path, series, options);
  return read_figure(path);
}

// Column range and row range of the pixels of colour `c` in a region: {c0, c1, r0, r1}, inclusive.
std::array<int, 4> extent(const Figure& f, const iga_test::Rgb& c, int c0, int c1, int r0, int r1) {
  std::array<int, 4> e{c1, c0, r1, r0};
  for (int r = std::max(r0, 0); r < std::min(r1, f.height); ++r)
    for (int x = std::max(c0, 0); x < std::min(c1, f.width); ++x)
      if (f.png.rgb(x, r) == c) e = {std::min(e[0], x), std::max(e[1], x), std::min(e[2], r), std::max(e[3], r)};
  return e;
}

int nearest(const std::vector<int>& lines, int v) {
  int d = 1 << 30;
  for (int l : lines) d = std::min(d, std::abs(l - v));
  return d;
}

}  // namespace

TEST(LoglogPlot, EveryDecadeHasAGridLineATickAndALabel) {
  test::TempDir dir;
  const Figure f = plot(dir, falling(), {.x_label = "x", .y_label = "y"});
  ASSERT_EQ(f.x_decades.size(), 4u);  // 10^1 .. 10^4
  ASSERT_EQ(f.y_decades.size(), 7u);  // 10^-7 .. 10^-1
  for (std::size_t i = 2; i < f.x_decades.size(); ++i)
    EXPECT_NEAR(f.x_decades[i] - f.x_decades[i - 1], f.x_decades[1] - f.x_decades[0], 1);
  for (std::size_t i = 2; i < f.y_decades.size(); ++i)
    EXPECT_NEAR(f.y_decades[i - 1] - f.y_decades[i], f.y_decades[0] - f.y_decades[1], 1);
  // Below the x axis: a two-pixel tick mark, then the label centred under it (the band starts below the
  // label of the lowest y decade, which is centred on the x axis).
  const int band_top = f.axis_row + 10, band_bottom = f.axis_row + 31;
  for (int c : f.x_decades) {
    EXPECT_EQ(f.count(black, c, c + 2, f.axis_row + 1, f.axis_row + 6), 10) << "tick at column " << c;
    EXPECT_GT(f.count(black, c - 10, c + 11, band_top, band_bottom), 20) << "label at column " << c;
  }
  // Left of the y axis: the tick mark, then the label ending left of it (the band stops above the label of the
  // lowest x decade, which is centred on the y axis).
  const int band_left = f.axis_col - 50, band_right = f.axis_col - 11, band_end = f.axis_row + 10;
  for (int r : f.y_decades) {
    EXPECT_EQ(f.count(black, f.axis_col - 5, f.axis_col, r - 1, r + 1), 10) << "tick at row " << r;
    EXPECT_GT(f.count(black, band_left, band_right, r - 6, r + 7), 20) << "label at row " << r;
  }
  // Text in these bands belongs to a decade: no label sits between two of them.
  for (int r = band_top; r < band_bottom; ++r)
    for (int x = 0; x < f.width; ++x)
      if (f.png.rgb(x, r) == black) {
        ASSERT_LE(nearest(f.x_decades, x), 20) << x << ", " << r;
      }
  for (int r = 0; r < band_end; ++r)
    for (int x = band_left; x < band_right; ++x)
      if (f.png.rgb(x, r) == black) {
        ASSERT_LE(nearest(f.y_decades, r), 10) << x << ", " << r;
      }
}

TEST(LoglogPlot, AxisLabelsAndTitleAreDrawnWhenGiven) {
  test::TempDir dir;
  const Figure plain = plot(dir, falling());
  // Nothing beyond the tick labels: below, to the left and above the box.
  EXPECT_EQ(plain.count(black, 0, plain.width, plain.axis_row + 32, plain.height), 0);
  EXPECT_EQ(plain.count(black, 0, plain.axis_col - 48, 0, plain.height), 0);
  EXPECT_EQ(plain.count(black, 0, plain.width, 0, plain.top() - 10), 0);

  const Figure f = plot(dir, falling(), {.x_label = "degrees of freedom", .y_label = "error", .title = "Convergence"});
  const int mid_col = (f.axis_col + f.right()) / 2, mid_row = (f.axis_row + f.top()) / 2;
  const auto x_label = extent(f, black, 0, f.width, f.axis_row + 32, f.height);
  EXPECT_NEAR((x_label[0] + x_label[1]) / 2, mid_col, 3);
  EXPECT_GT(x_label[1] - x_label[0], 5 * (x_label[3] - x_label[2]));  // one line of text
  const auto y_label = extent(f, black, 0, f.axis_col - 48, 0, f.height);
  EXPECT_NEAR((y_label[2] + y_label[3]) / 2, mid_row, 3);
  EXPECT_GT(y_label[3] - y_label[2], 3 * (y_label[1] - y_label[0]));  // turned upright
  const auto title = extent(f, black, 0, f.width, 0, f.top() - 10);
  EXPECT_NEAR((title[0] + title[1]) / 2, mid_col, 3);
  EXPECT_GT(title[1] - title[0], 5 * (title[3] - title[2]));
}

TEST(LoglogPlot, LegendNamesTheLabelledSeriesInAFreeCorner) {
  test::TempDir dir;
  auto series = falling();
  const Figure f = plot(dir, series);
  // The top-right quarter has no data, so what it shows there is the legend: colours, frame and names.
  EXPECT_GT(f.count_in_box(blue, 0.6, 1, 0.6, 1), 20);
  EXPECT_GT(f.count_in_box(red, 0.6, 1, 0.6, 1), 20);
  EXPECT_GT(f.count_in_box(black, 0.6, 1, 0.6, 1), 200);
  // A series without a plotted point is neither drawn nor listed.
  EXPECT_EQ(f.count(green, 0, f.width, 0, f.height), 0);

  for (auto& s : series) s.label.clear();
  const Figure bare = plot(dir, series);
  EXPECT_EQ(bare.count_in_box(blue, 0.6, 1, 0.6, 1), 0);
  EXPECT_EQ(bare.count_in_box(red, 0.6, 1, 0.6, 1), 0);
  EXPECT_EQ(bare.count_in_box(black, 0.6, 1, 0.6, 1), 0);
}

TEST(LoglogPlot, LegendMovesAwayFromTheData) {
  test::TempDir dir;
  // Rising along the diagonal: the top-right and bottom-left corners hold data, the top-left is free.
  const Figure f = plot(dir, {{{10, 100, 1000, 10000}, {1e-7, 1e-5, 1e-3, 1e-1}, blue, "rising"}});
  EXPECT_GT(f.count_in_box(black, 0.02, 0.5, 0.5, 0.98), 200);
  EXPECT_EQ(f.count_in_box(black, 0.5, 1, 0.5, 1), 0);
  EXPECT_GT(f.count_in_box(blue, 0.5, 1, 0.5, 1), 0);
}

TEST(LoglogPlot, BadInputThrows) {
  test::TempDir dir;
  const std::string path = dir.file("bad.png");
  EXPECT_THROW(write_loglog_plot(path, {}), Error);
  EXPECT_THROW(write_loglog_plot(path, {{{1, 2}, {0, -1}}}), Error);
  EXPECT_THROW(write_loglog_plot(path, falling(), {.width = 60, .height = 40}), Error);
  EXPECT_THROW(write_loglog_plot(dir.file("no/such/dir/p.png"), falling()), Error);
  EXPECT_EQ(dir.entries(), 0);
}
