#include "trivar/am/cell_section.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <utility>

#include "trivar/core/error.hpp"
#include "trivar/model/ball.hpp"
#include "trivar/model/block.hpp"
#include "trivar/model/cylinder.hpp"

using namespace trivar;
using namespace trivar::am;

namespace {

double length(const OutlineSegment& s) { return std::hypot(s.x1 - s.x0, s.y1 - s.y0); }

// Every end point of a non-degenerate segment is shared with another segment (bit-identical), i.e. the
// segments form closed polygons.
void expect_closed(const std::vector<OutlineSegment>& segs) {
  std::map<std::pair<double, double>, int> degree;
  for (const auto& s : segs) {
    if (s.x0 == s.x1 && s.y0 == s.y1) continue;
    ++degree[{s.x0, s.y0}];
    ++degree[{s.x1, s.y1}];
  }
  for (const auto& [p, d] : degree) EXPECT_EQ(d % 2, 0) << "open vertex at " << p.first << ", " << p.second;
}

}  // namespace

TEST(CellSection, BlockSectionIsItsRectangle) {
  // [0, 2] x [0, 3] x [0, 1], quadratic with several elements: the section at any height is the rectangle.
  const auto s = make_block<3>({2, 2, 2}, {2, 1, 3}, {2.0, 3.0, 1.0});
  const CellSection sec(s);
  std::vector<OutlineSegment> segs;
  sec.section(0.4, segs);
  ASSERT_FALSE(segs.empty());
  double perimeter = 0;
  for (const auto& g : segs) {
    perimeter += length(g);
    for (const auto& [x, y] : {std::pair{g.x0, g.y0}, std::pair{g.x1, g.y1}}) {
      const double to_edge = std::min({std::abs(x), std::abs(x - 2), std::abs(y), std::abs(y - 3)});
      EXPECT_LE(to_edge, 1e-14);
      EXPECT_GE(x, -1e-14);
      EXPECT_LE(x, 2 + 1e-14);
    }
  }
  EXPECT_NEAR(perimeter, 10.0, 1e-12);  // 2 (2 + 3)
  expect_closed(segs);
  segs.clear();
  sec.section(1.5, segs);
  sec.section(-0.1, segs);
  EXPECT_TRUE(segs.empty());
}

TEST(CellSection, BallCellsAreClosedAndFollowTheSphereWithinTolerance) {
  const double R = 5, tol = 1e-7;
  SectionOptions opt;
  opt.tolerance = tol;
  for (double z : {0.0, 1.3, -3.7, 4.6}) {
    const double rho = std::sqrt(R * R - z * z);
    std::vector<OutlineSegment> all;
    for (const auto& cell : make_ball({R})) {
      const CellSection sec(cell, opt);
      std::vector<OutlineSegment> segs;
      sec.section(z, segs);
      expect_closed(segs);
      all.insert(all.end(), segs.begin(), segs.end());
    }
    // The outer cells' faces w = 1 are on the sphere: vertices exactly on the circle of radius rho, chords
    // inside it by at most the tolerance; every vertex lies in the disk.
    int on_sphere = 0;
    double sphere_length = 0;
    for (const auto& g : all) {
      const double r0 = std::hypot(g.x0, g.y0), r1 = std::hypot(g.x1, g.y1);
      EXPECT_LE(r0, rho + 1e-12);
      EXPECT_LE(r1, rho + 1e-12);
      if (g.face != 5 || std::abs(r0 - rho) > 1e-9) continue;
      ++on_sphere;
      EXPECT_NEAR(r1, rho, 1e-11);
      const double rm = std::hypot(0.5 * (g.x0 + g.x1), 0.5 * (g.y0 + g.y1));
      EXPECT_LE(rho - rm, tol * 1.01);
      sphere_length += length(g);
    }
    EXPECT_GT(on_sphere, 100);
    EXPECT_NEAR(sphere_length, 2 * std::numbers::pi * rho, 1e-6 * rho);
  }
}

TEST(CellSection, CylinderCellsSpanTheDisk) {
  const CylinderSpec spec{1.5, 2.0};
  double rmax = 0;
  for (const auto& cell : make_cylinder(spec)) {
    const CellSection sec(cell);
    std::vector<OutlineSegment> segs;
    sec.section(0.7, segs);
    ASSERT_FALSE(segs.empty());
    expect_closed(segs);
    for (const auto& g : segs) rmax = std::max({rmax, std::hypot(g.x0, g.y0), std::hypot(g.x1, g.y1)});
  }
  EXPECT_NEAR(rmax, 1.5, 1e-12);
}

TEST(CellSection, RejectsBadInput) {
  const auto s = make_block<3>({1, 1, 1}, {1, 1, 1}, {1.0, 1.0, 1.0});
  SectionOptions bad;
  bad.samples_per_span = 0;
  EXPECT_THROW(CellSection(s, bad), Error);
  bad = {};
  bad.tolerance = 0;
  EXPECT_THROW(CellSection(s, bad), Error);
}
