// Convergence figure: L2 and H1 errors always, the estimate as a third series (and legend entry) only when the
// rows carry one. The coordinates are checked against the CSV by tests/io/output_files_test.py.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "support/temp_dir.hpp"
#include "trivar/iga/convergence_table.hpp"

using namespace trivar;

namespace {

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

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

}  // namespace

TEST(ConvergenceSvg, EstimateIsAThirdSeriesWhenComputed) {
  test::TempDir dir;
  for (bool estimate : {false, true}) {
    const std::string path = dir.file(estimate ? "with.svg" : "without.svg");
    write_convergence_svg(path, study(estimate));
    std::ifstream in(path);
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string svg = ss.str();
    EXPECT_EQ(count(svg, "<g class=\"series\""), estimate ? 3 : 2);
    EXPECT_EQ(count(svg, "<title>estimate</title>"), estimate ? 1 : 0);
    EXPECT_EQ(count(svg, "<circle"), 4 * (estimate ? 3 : 2) + (estimate ? 3 : 2));  // points and legend
    // Decade labels 10^1 .. 10^4 on x; 10^-5 .. 10^-1 on y, up to 10^0 with the estimate (0.2 > 10^-1).
    EXPECT_EQ(count(svg, "font-size=\"10\">"), 4 + (estimate ? 6 : 5));
  }
}
