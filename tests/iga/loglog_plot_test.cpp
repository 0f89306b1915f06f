// The log-log SVG plot: what it refuses. Its content (points on the decade axes, legend) is read back with an
// XML parser by tests/io/output_files_test.py.
#include "trivar/iga/loglog_plot.hpp"

#include <gtest/gtest.h>

#include "support/temp_dir.hpp"
#include "trivar/core/error.hpp"

using namespace trivar;

TEST(LogLogPlot, RefusesWhatCannotBeDrawnAndWritesNothing) {
  test::TempDir dir;
  const std::string path = dir.file("p.svg");
  const std::vector<PlotSeries> falling{{{10, 100}, {1e-1, 1e-3}, {0, 0, 255}, "e"}};
  EXPECT_THROW(write_loglog_plot(path, {}), Error);
  EXPECT_THROW(write_loglog_plot(path, {{{1, 2}, {0, -1}}}), Error);  // nothing positive
  EXPECT_THROW(write_loglog_plot(path, falling, {.width = 60, .height = 40}), Error);
  EXPECT_THROW(write_loglog_plot(dir.file("no/such/dir/p.svg"), falling), Error);
  EXPECT_EQ(dir.entries(), 0);
  write_loglog_plot(path, falling);
  EXPECT_EQ(dir.entries(), 1);
}
