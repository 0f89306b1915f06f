// exact_chart's cut flags against the T-spline of the whole mesh. A planar T-mesh without star points is its own
// chart, so its T-spline (every ray cast to the mesh's boundary) is the reference for the charts of face rings: a
// chart may call a member cut where it is exact, never exact where its value differs. The meshes are grids with knot
// segments (a knot inserted into some rows of a column or some columns of a row), whose T-junctions leave rows with
// and without the knot side by side: a blending function of a row without it reaches one knot line further than its
// neighbours, past the chart's border where the chart's rays stop.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include "chart_comparison.hpp"
#include "knot_grid.hpp"
#include "trivar/io/tsm_format.hpp"
#include "trivar/tspline/exact_chart.hpp"

namespace trivar {
namespace {

// A knot inserted into the vertex lines first..last of a grid (axis 0: s = s[line] + fraction (s[line + 1] -
// s[line]) into the rows first..last; axis 1: t likewise into the columns): the faces between those lines are
// split, the two faces beyond its ends become T-faces. New points on the grid's wavy surface.
struct KnotInsertion {
  int axis, line;
  double fraction;
  int first, last;
};

void insert_segment(test::Grid& g, const KnotInsertion& k) {
  test::QuadMesh& q = g.quads;
  const std::vector<double>& along = k.axis == 0 ? g.s : g.t;
  const double at = along[static_cast<std::size_t>(k.line)] + k.fraction * (along[static_cast<std::size_t>(k.line + 1)] - along[static_cast<std::size_t>(k.line)]);
  // Vertex (a, b): a across the segment (the grid's index along `axis`), b along it.
  const auto id = [&](int a, int b) { return k.axis == 0 ? g.id(a, b) : g.id(b, a); };
  const auto coord = [&](int b) { return (k.axis == 0 ? g.t : g.s)[static_cast<std::size_t>(b)]; };
  std::vector<int> added;  // per line b = first..last
  for (int b = k.first; b <= k.last; ++b) {
    const double s = k.axis == 0 ? at : coord(b), t = k.axis == 0 ? coord(b) : at;
    const double x = s + 0.1 * t, y = t - 0.05 * s;  // as test::grid
    added.push_back(static_cast<int>(q.points.size()));
    q.points.push_back({x, y, test::wave(x, y)});
  }
  const auto mid = [&](int b) { return added[static_cast<std::size_t>(b - k.first)]; };
  const double low = at - along[static_cast<std::size_t>(k.line)], high = along[static_cast<std::size_t>(k.line + 1)] - at;
  for (int b = k.first; b <= k.last; ++b) {
    q.intervals[{id(k.line, b), mid(b)}] = low;
    q.intervals[{mid(b), id(k.line + 1, b)}] = high;
    if (b < k.last) q.intervals[{mid(b), mid(b + 1)}] = coord(b + 1) - coord(b);
  }
  // The quads as lists from a corner counter-clockwise; the face's corners (a, b) .. (a + 1, b + 1) in the grid's
  // (s, t) order, with axis 1 mirrored so that the loops stay counter-clockwise.
  const auto corners = [&](int b) {
    const int a = k.line;
    return k.axis == 0 ? std::array<int, 4>{id(a, b), id(a + 1, b), id(a + 1, b + 1), id(a, b + 1)}
                       : std::array<int, 4>{id(a, b), id(a, b + 1), id(a + 1, b + 1), id(a + 1, b)};
  };
  std::vector<std::array<int, 4>> quads;
  for (const auto& f : q.quads) {
    bool split = false;
    for (int b = k.first - 1; b <= k.last; ++b) split = split || f == corners(b);
    if (!split) quads.push_back(f);
  }
  for (int b = k.first; b < k.last; ++b) {
    const auto c = corners(b);
    if (k.axis == 0) {
      quads.push_back({c[0], mid(b), mid(b + 1), c[3]});
      quads.push_back({mid(b), c[1], c[2], mid(b + 1)});
    } else {
      quads.push_back({c[0], c[1], mid(b + 1), mid(b)});
      quads.push_back({mid(b), mid(b + 1), c[2], c[3]});
    }
  }
  // Before the first line the new vertex lies on the face's side from (a + 1, first) to (a, first), after the last
  // on its side from (a, last) to (a + 1, last); in the loops of axis 1 the sides run the other way.
  const auto before = corners(k.first - 1), after = corners(k.last);
  if (k.axis == 0) {
    q.t_faces.push_back({{before[0], before[1], before[2], mid(k.first), before[3]}, {0, 0, 0, 1, 0}});
    q.t_faces.push_back({{after[0], mid(k.last), after[1], after[2], after[3]}, {0, 1, 0, 0, 0}});
  } else {
    q.t_faces.push_back({{before[0], before[1], mid(k.first), before[2], before[3]}, {0, 0, 1, 0, 0}});
    q.t_faces.push_back({{after[0], after[1], after[2], after[3], mid(k.last)}, {0, 0, 0, 0, 1}});
  }
  q.quads = std::move(quads);
}

// The grid of 12 x 11 faces on unequal intervals with knot segments; by default one in column 4 over rows 3..6 and
// one in row 7 over columns 6..9.
struct SegmentMesh {
  test::Grid grid;
  TMesh mesh;
};
SegmentMesh segment_mesh(const std::vector<KnotInsertion>& segments = {{0, 4, 0.35, 3, 6}, {1, 7, 0.4, 6, 9}}) {
  SegmentMesh r{test::grid({0, 1, 2.5, 3.5, 4.5, 5.5, 6.25, 7.25, 8.25, 9.5, 10.5, 11.5, 12.5},
                           {0, 1, 2, 3.5, 4.5, 5.5, 6.5, 7.5, 8.75, 9.75, 10.75, 11.75}),
                 {}};
  for (const KnotInsertion& k : segments) insert_segment(r.grid, k);
  r.mesh = io::parse_tsm(test::tsm_text(r.grid.quads), "segments.tsm").mesh;
  return r;
}

bool has_vertex(const TMesh& m, int f, int v) {
  const auto& loop = m.faces[static_cast<std::size_t>(f)];
  return std::any_of(loop.begin(), loop.end(), [&](int l) { return m.links[static_cast<std::size_t>(l)].vertex == v; });
}

// The largest difference in position between face j of chart a and face i of chart b (the same face) over
// points inside it.
double chart_gap(const ExactChart& a, std::size_t j, const ExactChart& b, std::size_t i) {
  double gap = 0;
  for (double u : {0.1, 0.5, 0.85})
    for (double v : {0.15, 0.5, 0.9}) {
      const auto at = [&](const ExactChart::Frame& f) {
        return Param<2>{f.origin[0] + u * f.axis_u[0] + v * f.axis_v[0], f.origin[1] + u * f.axis_u[1] + v * f.axis_v[1]};
      };
      double p[3], q[3];
      a.surface->eval(at(a.frames[j]), p);
      b.surface->eval(at(b.frames[i]), q);
      for (int k = 0; k < 3; ++k) gap = std::max(gap, std::abs(p[k] - q[k]));
    }
  return gap;
}

std::vector<int> every_face(const TMesh& m) {
  std::vector<int> f(m.faces.size());
  for (std::size_t i = 0; i < f.size(); ++i) f[i] = static_cast<int>(i);
  return f;
}

// The narrow face next to the knot line in the segment's first split row: its two rings hold the vertex diagonally
// below it in a row without the knot, whose ray towards the far side stops at the rings' border one knot line
// short. The chart's value there is not the T-spline's, so the face is cut.
TEST(ChartCut, BorderThatStopsARayCutsTheFace) {
  const SegmentMesh sm = segment_mesh();
  const TMesh& m = sm.mesh;
  const std::vector<int> faces = every_face(m);
  // The faces at (4, 3) and (4, 4) are the split one on the knot line's near side and the one west of it.
  int f = -1;
  for (int g : faces)
    if (has_vertex(m, g, sm.grid.id(4, 3)) && has_vertex(m, g, sm.grid.id(4, 4)) && !has_vertex(m, g, sm.grid.id(3, 3))) f = g;
  ASSERT_GE(f, 0);
  ASSERT_EQ(m.faces[static_cast<std::size_t>(f)].size(), 4u);
  const ExactChart whole = exact_chart(m, faces, f, faces, 1);
  EXPECT_EQ(std::count(whole.cut.begin(), whole.cut.end(), 1), 0);  // no border inside the mesh
  const std::vector<int> member{f};
  const ExactChart two = exact_chart(m, test::face_rings(m, f, 2), f, member, 1), three = exact_chart(m, test::face_rings(m, f, 3), f, member, 1);
  const double gap2 = chart_gap(two, 0, whole, static_cast<std::size_t>(f)), gap3 = chart_gap(three, 0, whole, static_cast<std::size_t>(f));
  EXPECT_TRUE(two.whole[0]);
  EXPECT_GT(gap2, 1e-4);
  EXPECT_TRUE(two.cut[0]);
  EXPECT_LT(gap3, 1e-13);
  EXPECT_FALSE(three.cut[0]);
  std::printf("narrow face %d against the whole mesh's T-spline: two rings %.1e (cut %d), three rings %.1e (cut %d)\n", f, gap2,
              two.cut[0], gap3, three.cut[0]);
}

// Every face in the charts of its 1, 2 and 3 face rings (and the faces of its ring 1 as members): where exact_chart
// calls a member uncut, its value is the T-spline's. Besides the default segments, segments in neighbouring columns
// with overlapping rows, one in the boundary row and one in the row above a column's segment.
TEST(ChartCut, UncutMembersAreTheTSpline) {
  for (const std::vector<KnotInsertion>& segments :
       {std::vector<KnotInsertion>{{0, 4, 0.35, 3, 6}, {1, 7, 0.4, 6, 9}},
        std::vector<KnotInsertion>{{0, 2, 0.5, 2, 8}, {0, 3, 0.3, 4, 6}, {1, 9, 0.6, 1, 5}, {1, 0, 0.5, 7, 10}}}) {
    const TMesh m = segment_mesh(segments).mesh;
    const std::vector<int> faces = every_face(m);
    const ExactChart whole = exact_chart(m, faces, 0, faces, 1);
    std::array<int, 4> uncut{}, cut{};
    double worst = 0;
    for (int f : faces)
      for (int r = 1; r <= 3; ++r) {
        const std::vector<int> members = test::face_rings(m, f, 1);
        const ExactChart c = exact_chart(m, test::face_rings(m, f, r), f, members, 1);
        for (std::size_t j = 0; j < members.size(); ++j) {
          if (c.cut[j]) {
            ++cut[static_cast<std::size_t>(r)];
            continue;
          }
          ++uncut[static_cast<std::size_t>(r)];
          const double gap = chart_gap(c, j, whole, static_cast<std::size_t>(members[j]));
          worst = std::max(worst, gap);
          EXPECT_LT(gap, 1e-12) << "face " << members[j] << " in the chart of " << r << " rings round face " << f;
        }
      }
    // Three rings hold the knot vectors of most faces.
    EXPECT_GT(uncut[3], cut[3]);
    std::printf("%zu segments: members uncut / cut in charts of 1, 2, 3 rings: %d / %d, %d / %d, %d / %d; largest gap of an uncut member %.1e\n",
                segments.size(), uncut[1], cut[1], uncut[2], cut[2], uncut[3], cut[3], worst);
  }
}

}  // namespace
}  // namespace trivar
