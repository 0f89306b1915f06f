// Star points on the boundary of a T-mesh: Catmull-Clark on the control mesh extended by a ghost layer whose
// regular part is the T-spline's Bezier end condition (boundary_ghosts). Known answers: a regular boundary vertex
// reproduces the clamped bicubic T-spline through the ghost layer; faces whose points avoid the star point are
// the T-spline of their charts; the boundary curve is the cubic B-spline of the end-condition block points;
// positions, normals and first derivatives agree across every interior edge; the tessellation is watertight.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "boundary_star_checks.hpp"
#include "chart_comparison.hpp"
#include "face_continuity.hpp"
#include "star_mesh_tsm.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/tsm_format.hpp"
#include "trivar/tspline/boundary_ghosts.hpp"
#include "trivar/tspline/catmull_clark_patch.hpp"
#include "trivar/tspline/t_mesh_patches.hpp"
#include "trivar/tspline/t_mesh_surface.hpp"
#include "trivar/tspline/t_mesh_tessellation.hpp"

namespace trivar {
namespace {

double bump(double x, double y) { return 0.3 * std::sin(0.7 * x + 0.2) * std::cos(0.5 * y) + 0.05 * x * y; }

// The model of a half fan with its end-condition block points moved off their vertices (the general clamped end:
// Q0 != Q1), by a random offset each.
io::TsmModel half_fan_model(int sectors, int m, unsigned seed) {
  io::TsmModel model = io::parse_tsm(tsm_text(test::half_fan_mesh(sectors, m, bump)), "half_fan.tsm");
  test::offset_block_points(model.mesh, seed);
  return model;
}

const std::array<double, 3>& point_of(const TMesh& m, int v) {
  return m.points[static_cast<std::size_t>(m.vertices[static_cast<std::size_t>(v)].primary)].xyz;
}

int vertex_at(const TMesh& m, double x, double y) {
  for (int v = 0; v < static_cast<int>(m.vertices.size()); ++v) {
    const auto& p = point_of(m, v);
    if (std::abs(p[0] - x) < 1e-12 && std::abs(p[1] - y) < 1e-12) return v;
  }
  return -1;
}

TEST(BoundaryStar, RegularBoundaryVertexThroughTheGhostLayerIsTheClampedBicubicTSpline) {
  // K = 2: the grid [-4, 4] x [0, 4] with a straight boundary; no star point, so every face is the T-spline.
  const io::TsmModel model = half_fan_model(2, 4, 11);
  const TMesh& m = model.mesh;
  const TMeshSurface s(m, 1);
  ASSERT_EQ(s.count(FaceMethod::exact), s.num_faces());
  const int centre = vertex_at(m, 0, 0);
  ASSERT_GE(centre, 0);
  const std::array<int, 1> stars{centre};
  const GhostedMesh g = ghost_boundary(m, stars, 3);
  // The uniform bicubic patch of the extended mesh on the face [a, a + 1] x [0, 1]: rows -1 (ghosts) .. 2.
  for (int a = -2; a <= 1; ++a) {
    std::array<std::array<double, 3>, 16> grid{};
    for (int j = -1; j <= 2; ++j)
      for (int i = -1; i <= 2; ++i) {
        const int v = vertex_at(m, a + i, std::max(j, 0));
        ASSERT_GE(v, 0);
        const int w = j < 0 ? g.ghost[static_cast<std::size_t>(v)] : v;
        ASSERT_GE(w, 0) << a + i;
        grid[static_cast<std::size_t>((i + 1) + 4 * (j + 1))] = point_of(g.mesh, w);
      }
    // The face [a, a + 1] x [0, 1] and its frame in the grid's (x, y).
    int face = -1;
    for (int f = 0; f < s.num_faces(); ++f) {
      const auto c = s.corners(f);
      double lo = 1e9;
      for (int v : c) lo = std::min(lo, point_of(m, v)[0]);
      if (std::abs(lo - a) < 1e-12 && std::all_of(c.begin(), c.end(), [&](int v) { return point_of(m, v)[1] < 1.5; })) face = f;
    }
    ASSERT_GE(face, 0) << a;
    const auto c = s.corners(face);
    const auto& c0 = point_of(m, c[0]);
    const auto& c1 = point_of(m, c[1]);
    const auto& c3 = point_of(m, c[3]);
    for (double u : {0.0, 0.3, 0.5, 1.0})
      for (double v : {0.0, 0.2, 0.7, 1.0}) {
        const double sx = c0[0] + u * (c1[0] - c0[0]) + v * (c3[0] - c0[0]) - a, ty = c0[1] + u * (c1[1] - c0[1]) + v * (c3[1] - c0[1]);
        double x[9], y[9];
        eval_uniform_bicubic(grid, sx, ty, x);
        s.eval(face, u, v, y);
        for (int k = 0; k < 3; ++k) {
          EXPECT_NEAR(x[k], y[k], 1e-12) << a << ' ' << u << ' ' << v << ' ' << k;
          EXPECT_NEAR((c1[0] - c0[0]) * x[3 + k] + (c1[1] - c0[1]) * x[6 + k], y[3 + k], 1e-12) << a << ' ' << u << ' ' << v;
          EXPECT_NEAR((c3[0] - c0[0]) * x[3 + k] + (c3[1] - c0[1]) * x[6 + k], y[6 + k], 1e-12) << a << ' ' << u << ' ' << v;
        }
      }
  }
}

// The boundary's faces [i, i + 1] x [0, 1] along spoke 0 (sector 0) and [0, 1] x [j, j + 1] along spoke K: their
// boundary side against the uniform cubic B-spline of the block points (closed form).
double boundary_curve_defect(const TMeshSurface& s, const TMesh& m, int sectors, int rings, int first) {
  const auto block = [&](int v) { return m.points[static_cast<std::size_t>(m.vertices[static_cast<std::size_t>(v)].block.at(0))].xyz; };
  double worst = 0;
  for (int side = 0; side < 2; ++side)
    for (int i = first; i + 3 <= rings; ++i) {  // off the clamped ends at the outer corners
      const int k = side == 0 ? 0 : sectors - 1;
      const int f = side == 0 ? k * rings * rings + i : k * rings * rings + i * rings;
      const auto c = s.corners(f);
      // The boundary vertices b(i - 1) .. b(i + 2) along the spoke, from the face's boundary corners outwards.
      const int from = side == 0 ? c[0] : c[3], to = side == 0 ? c[1] : c[0];
      const auto& p0 = point_of(m, from);
      const auto& p1 = point_of(m, to);
      const double dx = p1[0] - p0[0], dy = p1[1] - p0[1];
      std::array<std::array<double, 3>, 4> b;
      for (int t = -1; t <= 2; ++t) {
        const int v = vertex_at(m, p0[0] + t * dx, p0[1] + t * dy);
        if (v < 0) return 1;
        b[static_cast<std::size_t>(t + 1)] = block(v);
      }
      for (double t : {0.0, 0.25, 0.5, 0.8, 1.0}) {
        const double w[4] = {(1 - t) * (1 - t) * (1 - t) / 6, (3 * t * t * t - 6 * t * t + 4) / 6, (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6, t * t * t / 6};
        double x[9];
        if (side == 0)
          s.eval(f, t, 0, x);
        else
          s.eval(f, 0, 1 - t, x);
        for (std::size_t q = 0; q < 3; ++q) {
          double r = 0;
          for (std::size_t a = 0; a < 4; ++a) r += w[a] * b[a][q];
          worst = std::max(worst, std::abs(r - x[q]));
        }
      }
    }
  return worst;
}

class BoundaryStarValence : public ::testing::TestWithParam<int> {};

TEST_P(BoundaryStarValence, LoadsAsOneSmoothSurfaceWithTheTSplineAwayFromTheStarPoint) {
  const int sectors = GetParam(), rings = 7;
  const io::TsmModel model = half_fan_model(sectors, rings, 5u + static_cast<unsigned>(sectors));
  EXPECT_EQ(model.report.star_points, 1);
  const TMesh& m = model.mesh;
  const TMeshSurface s(m, 1);
  EXPECT_EQ(s.count(FaceMethod::star), sectors);
  EXPECT_EQ(s.boundary_star_faces(), sectors);
  EXPECT_EQ(s.count(FaceMethod::star) + s.count(FaceMethod::bicubic) + s.count(FaceMethod::exact), sectors * rings * rings);
  EXPECT_GT(s.count(FaceMethod::exact), 0);
  // The Catmull-Clark faces whose two rings hold no star point: the T-spline of their charts (with its Bezier
  // end conditions at the boundary, block points off their vertices).
  const test::ChartComparison cmp = test::compare_with_charts(m, s, FaceMethod::bicubic);
  EXPECT_GT(cmp.compared, 4);
  EXPECT_LT(cmp.position, 1e-12);
  EXPECT_LT(cmp.derivative, 1e-11);
  // Boundary curve: the cubic B-spline of the block points from two faces along the boundary on.
  EXPECT_LT(boundary_curve_defect(s, m, sectors, rings, 2), 1e-12);
  // Across every interior edge (also those at the star point, away from it): positions, normals, C1.
  const test::Continuity c = test::continuity(m, [&](int f, double u, double v, double* o) { s.eval(f, u, v, o); });
  EXPECT_LT(c.gap, 1e-12);
  EXPECT_LT(c.normal_angle, 1e-10);
  EXPECT_LT(c.c1, 1e-10);
  std::printf("boundary star of %d faces: %d edges, gap %.2e, normal defect (sin) %.2e, C1 defect %.2e; %d faces as charts "
              "(position %.2e)\n", sectors, c.edges, c.gap, c.normal_angle, c.c1, cmp.compared, cmp.position);
  // One tangent plane at the star point for all its faces.
  EXPECT_LT(test::tangent_plane_spread(s, s.stars()[0]), 1e-9);
  const TSplineTriangulation t = tessellate(s, 1e-2);
  for (const auto& p : t.points) ASSERT_TRUE(std::isfinite(p[0] + p[1] + p[2]));
  EXPECT_EQ(test::boundary_loops(t), 1);
  // Bezier patches (exact pieces, one corner patch per star face) within their tolerance of the limit surface.
  if (sectors == 5) {
    const TMeshPatches p = t_mesh_patches(s);
    EXPECT_GT(p.patches.size(), static_cast<std::size_t>(s.num_faces()));
    EXPECT_LE(p.deviation, p.tolerance);
  }
}

INSTANTIATE_TEST_SUITE_P(Faces, BoundaryStarValence, ::testing::Values(4, 5, 6));

// The outside link at a boundary star point of K faces: Rhino's flag is the outside's angle / 90 - 1 = 3 - K (as
// 2, 1, 0 after one, two, three faces); 0 there (the angle clamped) reads as the same mesh; other negative flags
// are refused. (BoundaryStarValence reads the 3 - K form.)
TEST(BoundaryStar, OutsideFlagIsTheOutsidesAngleOrZero) {
  const test::QuadMesh fan = test::half_fan_mesh(4, 7, bump);
  const std::string angle = tsm_text(fan), clamped = tsm_text(fan, 1.0, true);
  const io::TsmModel a = io::parse_tsm(angle, "angle.tsm"), b = io::parse_tsm(clamped, "clamped.tsm");
  // The star point is vertex 0; its outside link's line "l prev next opp 0 -1 edge flag".
  const auto outside_flag = [](const TMesh& m) {
    for (const TMeshLink& k : m.links)
      if (k.vertex == 0 && k.face < 0) return k.flag;
    return 99;
  };
  EXPECT_EQ(outside_flag(a.mesh), -1);
  EXPECT_EQ(outside_flag(b.mesh), 0);
  const TMeshSurface sa(a.mesh, 1), sb(b.mesh, 1);
  ASSERT_EQ(sa.num_faces(), sb.num_faces());
  EXPECT_EQ(sa.count(FaceMethod::star), 4);
  for (int f = 0; f < sa.num_faces(); ++f) {
    EXPECT_EQ(sa.method(f), sb.method(f));
    double x[9], y[9];
    sa.eval(f, 0.3, 0.6, x);
    sb.eval(f, 0.3, 0.6, y);
    for (int i = 0; i < 9; ++i) EXPECT_EQ(x[i], y[i]) << f;
  }
  // -2 after four faces: neither the outside's angle nor a flag of 0..2.
  std::istringstream in(angle);
  std::string line, bad;
  while (std::getline(in, line)) {
    std::istringstream w(line);
    std::string tag;
    int prev = 0, next = 0, opp = 0, vertex = 0, face = 0, edge = 0, flag = 0;
    if ((w >> tag >> prev >> next >> opp >> vertex >> face >> edge >> flag) && tag == "l" && vertex == 0 && face == -1)
      line = line.substr(0, line.rfind(' ')) + " -2";
    bad += line + '\n';
  }
  ASSERT_NE(bad, angle);
  try {
    (void)io::parse_tsm(bad, "bad.tsm");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("corner flag -2 on the boundary at vertex 0"), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}

// A slit of 8 edges inside a grid: its two ends are star points of four faces on one boundary loop, 8 edges apart,
// so their ghost layers (7 edges either way) overlap and close round the slit as one layer.
TEST(BoundaryStar, TwoStarPointsAtTheEndsOfASlitShareOneGhostLayer) {
  const io::TsmModel model = io::parse_tsm(tsm_text(test::slit_mesh(22, 14, 7, 7, 15, bump)), "slit.tsm");
  EXPECT_EQ(model.report.star_points, 2);
  const TMesh& m = model.mesh;
  const TMeshSurface s(m, 1);
  ASSERT_EQ(s.stars().size(), 2u);
  EXPECT_EQ(s.count(FaceMethod::star), 8);
  EXPECT_EQ(s.boundary_star_faces(), 8);
  EXPECT_EQ(s.count(FaceMethod::star) + s.count(FaceMethod::bicubic) + s.count(FaceMethod::exact), 22 * 14);
  EXPECT_GT(s.count(FaceMethod::exact), 0);
  // Faces along the slit whose two rings avoid both star points: the T-spline of their charts (clamped at the
  // slit's sides).
  const test::ChartComparison cmp = test::compare_with_charts(m, s, FaceMethod::bicubic);
  EXPECT_GT(cmp.compared, 4);
  EXPECT_LT(cmp.position, 1e-12);
  EXPECT_LT(cmp.derivative, 1e-11);
  const test::Continuity c = test::continuity(m, [&](int f, double u, double v, double* o) { s.eval(f, u, v, o); });
  EXPECT_LT(c.gap, 1e-12);
  EXPECT_LT(c.normal_angle, 1e-10);
  EXPECT_LT(c.c1, 1e-10);
  std::printf("slit with two boundary star points: %d edges, gap %.2e, normal defect (sin) %.2e, C1 defect %.2e; %d faces as "
              "charts (position %.2e)\n", c.edges, c.gap, c.normal_angle, c.c1, cmp.compared, cmp.position);
  for (int star : s.stars()) EXPECT_LT(test::tangent_plane_spread(s, star), 1e-9) << star;
  // The slit's two sides end at the same block points (the same boundary curve): watertight apart from the slit,
  // whose boundary is the second loop.
  const TSplineTriangulation t = tessellate(s, 1e-2);
  for (const auto& p : t.points) ASSERT_TRUE(std::isfinite(p[0] + p[1] + p[2]));
  EXPECT_EQ(test::boundary_loops(t), 2);
}

// What the ghost layer cannot hold is refused with one line naming it.
TEST(BoundaryStar, RefusesShortCornerSidesTJunctionsAndUnequalIntervalsNearby) {
  const auto refused = [](const std::string& text, const std::string& fragment) {
    try {
      const io::TsmModel model = io::parse_tsm(text, "bad.tsm");
      const TMeshSurface s(model.mesh, 1);
      ADD_FAILURE() << "no error for " << fragment;
    } catch (const Error& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find(fragment), std::string::npos) << msg;
      EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    }
  };
  // One face per sector: the star point's boundary neighbours are corners whose other sides have one edge.
  refused(tsm_text(test::half_fan_mesh(4, 1, bump)), "a corner with a side of one edge");
  // A T-junction on the boundary two edges from the star point: the boundary side of sector 0's face [2, 3] x
  // [0, 1] split at its middle.
  test::QuadMesh split = test::half_fan_mesh(4, 7, bump);
  {
    const std::array<int, 4> f = split.quads[2];
    const int mid = static_cast<int>(split.points.size());
    split.points.push_back({2.5, 0, bump(2.5, 0)});
    split.quads.erase(split.quads.begin() + 2);
    split.t_faces.push_back({{f[0], mid, f[1], f[2], f[3]}, {0, 1, 0, 0, 0}});
    split.intervals[{f[0], mid}] = split.intervals[{mid, f[1]}] = 0.5;
  }
  refused(tsm_text(split), "T-junction");
  // A knot interval of 2 on the strip of the first faces along spoke 1.
  test::QuadMesh uneven = test::half_fan_mesh(4, 7, bump);
  for (int i = 0; i < 7; ++i) {
    const auto& f = uneven.quads[static_cast<std::size_t>(7 * 7 + i)];  // sector 1, row 0
    uneven.intervals[{f[0], f[3]}] = uneven.intervals[{f[1], f[2]}] = 2;
  }
  refused(tsm_text(uneven), "knot interval");
}

}  // namespace
}  // namespace trivar
