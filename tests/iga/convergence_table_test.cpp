// Convergence figure: L2 and H1 errors always, the estimate as a third series (and legend entry) only when the
// rows carry one, and both axes labelled.
#include <gtest/gtest.h>

#include "iga/plot_figure.hpp"
#include "support/temp_dir.hpp"
#include "trivar/iga/convergence_table.hpp"

using namespace trivar;
using iga_test::black;

namespace {

constexpr iga_test::Rgb blue{30, 80, 220}, red{220, 40, 40}, green{40, 150, 60};

// A uniform study in 3D; the estimate sits just above the H1 error.
std::vector<ConvergenceRow> study(bool estimate) {
  const int dofs[] = {27, 125, 729, 4913};
  const double l2[] = {1e-2, 1.5e-3, 2e-4, 2.5e-5}, h1[] = {1e-1, 3e-2, 8e-3, 2e-3};
  std::vector<ConvergenceRow> rows;
  for (int i = 0; i < 4; ++i)
    rows.push_back({.step = i, .elements = 1 << (3 * i), .dofs = dofs[i], .l2 = l2[i], .h1 = h1[i],
                    .estimate = estimate ? 2 * h1[i] : -1});
  return rows;
}

}  // namespace

TEST(ConvergencePng, EstimateIsAThirdSeriesWhenComputed) {
  test::TempDir dir;
  for (bool estimate : {false, true}) {
    const std::string path = dir.file(estimate ? "with.png" : "without.png");
    write_convergence_png(path, study(estimate));
    const auto f = iga_test::read_figure(path);
    EXPECT_GT(f.count(blue, 0, f.width, 0, f.height), 100);
    EXPECT_GT(f.count(red, 0, f.width, 0, f.height), 100);
    if (estimate) {
      // The data stay below 0.8 of the box's height on its right part: the green there is the legend entry.
      EXPECT_GT(f.count_in_box(green, 0.6, 1, 0.8, 1), 20);
      EXPECT_GT(f.count(green, 0, f.width, 0, f.height), 100);
    } else {
      EXPECT_EQ(f.count(green, 0, f.width, 0, f.height), 0);
    }
    // Axis labels: text below the x tick labels and left of the y tick labels.
    EXPECT_GT(f.count(black, 0, f.width, f.axis_row + 32, f.height), 100);
    EXPECT_GT(f.count(black, 0, f.axis_col - 48, 0, f.height), 50);
  }
}
