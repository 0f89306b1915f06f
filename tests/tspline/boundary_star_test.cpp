// Star points on the boundary of a T-mesh: Catmull-Clark on the control mesh extended by a ghost layer whose
// regular part is the T-spline's Bezier end condition (boundary_ghosts). Known answers: a regular boundary vertex
// reproduces the clamped bicubic T-spline through the ghost layer; faces whose points avoid the star point are
// the T-spline of their charts; the boundary curve is the cubic B-spline of the end-condition block points;
// positions, normals and first derivatives agree across every interior edge; the tessellation is watertight.
// Near corners of the boundary (the layer goes round them as the tensor product of the clamped ends) the same,
// and the limit point at a corner is its diagonal block point.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "chart_comparison.hpp"
#include "face_continuity.hpp"
#include "patch_check.hpp"
#include "star_mesh_tsm.hpp"
#include "triangulation_loops.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/tsm_format.hpp"
#include "trivar/tspline/boundary_ghosts.hpp"
#include "trivar/tspline/catmull_clark_patch.hpp"
#include "trivar/tspline/homogeneous_point.hpp"
#include "trivar/tspline/t_mesh_patches.hpp"
#include "trivar/tspline/t_mesh_surface.hpp"
#include "trivar/tspline/t_mesh_tessellation.hpp"
#include "trivar/tspline/t_spline_surface.hpp"

namespace trivar {
namespace {

double bump(double x, double y) { return 0.3 * std::sin(0.7 * x + 0.2) * std::cos(0.5 * y) + 0.05 * x * y; }

// The model of a quad mesh with its end-condition block points moved off their vertices (the general clamped end:
// Q0 != Q1), by a random offset each.
io::TsmModel offset_model(const test::QuadMesh& q, unsigned seed, double offset = 0.2) {
  io::TsmModel model = io::parse_tsm(tsm_text(q), "boundary_star.tsm");
  std::mt19937 g(seed);
  std::uniform_real_distribution<double> d(-offset, offset);
  for (const TMeshVertex& v : model.mesh.vertices)
    for (int b : v.block)
      if (b >= 0)
        for (double& c : model.mesh.points[static_cast<std::size_t>(b)].xyz) c += d(g);
  return model;
}

io::TsmModel half_fan_model(int sectors, int m, unsigned seed) { return offset_model(test::half_fan_mesh(sectors, m, bump), seed); }

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

// The faces around star point `star` have one tangent plane there: the largest sine of the angle between
// their normals and the first one's.
double tangent_plane_spread(const TMeshSurface& s, int star) {
  std::array<double, 3> n0{};
  double worst = 0;
  for (int f = 0; f < s.num_faces(); ++f) {
    const auto c4 = s.corners(f);
    const int corner = static_cast<int>(std::find(c4.begin(), c4.end(), star) - c4.begin());
    if (corner == 4) continue;
    const auto o = corner_frame(corner).origin;
    double x[9];
    s.eval(f, o[0], o[1], x);
    const auto n = test::unit_normal(x);
    if (n0 == std::array<double, 3>{}) n0 = n;
    worst = std::max(worst, std::hypot(n[1] * n0[2] - n[2] * n0[1], n[2] * n0[0] - n[0] * n0[2], n[0] * n0[1] - n[1] * n0[0]));
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
  EXPECT_LT(tangent_plane_spread(s, s.stars()[0]), 1e-9);
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
  for (int star : s.stars()) EXPECT_LT(tangent_plane_spread(s, star), 1e-9) << star;
  // The slit's two sides end at the same block points (the same boundary curve): watertight apart from the slit,
  // whose boundary is the second loop.
  const TSplineTriangulation t = tessellate(s, 1e-2);
  for (const auto& p : t.points) ASSERT_TRUE(std::isfinite(p[0] + p[1] + p[2]));
  EXPECT_EQ(test::boundary_loops(t), 2);
}

// What the ghost layer cannot hold is refused with one line naming it.
TEST(BoundaryStar, RefusesShortCornerSidesAndStripsOfTwoIntervals) {
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
  // A knot interval of 2 on the first faces along spoke 1 in sector 1 but not where their strip goes on round the
  // star point (sector 2's first faces along spoke 3): sector 2's face at the star point has sides of 2 and 1.
  test::QuadMesh uneven = test::half_fan_mesh(4, 7, bump);
  for (int i = 0; i < 7; ++i) {
    const auto& f = uneven.quads[static_cast<std::size_t>(7 * 7 + i)];  // sector 1, row 0
    uneven.intervals[{f[0], f[3]}] = uneven.intervals[{f[1], f[2]}] = 2;
  }
  refused(tsm_text(uneven), "face 98 nearby has knot intervals 2.000000 and 1.000000 on opposite sides");
}

// Star points near corners of the boundary, and two star points on one open stretch of boundary: the ghost layer
// goes round the corners as the tensor product of the clamped ends.
constexpr double kDegree = std::numbers::pi / 180;

// Quad meshes glued from parallelogram sectors: the sector of nu x nv faces at c spanned by the unit directions at
// angles au < av (degrees); vertices at the same position are one.
struct SectorMesh {
  test::QuadMesh q;
  std::map<std::array<long long, 2>, int> ids;

  int vertex(double x, double y) {
    const auto [it, fresh] = ids.emplace(std::array<long long, 2>{std::llround(x * 1e6), std::llround(y * 1e6)}, static_cast<int>(q.points.size()));
    if (fresh) q.points.push_back({x, y, bump(x, y)});
    return it->second;
  }
  std::array<double, 2> at(std::array<double, 2> c, double au, double av, int i, int j) const {
    return {c[0] + i * std::cos(au * kDegree) + j * std::cos(av * kDegree), c[1] + i * std::sin(au * kDegree) + j * std::sin(av * kDegree)};
  }
  void sector(std::array<double, 2> c, double au, double av, int nu, int nv) {
    for (int j = 0; j < nv; ++j)
      for (int i = 0; i < nu; ++i) {
        std::array<int, 4> f{};
        const std::array<std::array<int, 2>, 4> corner{{{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}}};
        for (std::size_t k = 0; k < 4; ++k) {
          const auto p = at(c, au, av, corner[k][0], corner[k][1]);
          f[k] = vertex(p[0], p[1]);
        }
        q.quads.push_back(f);
      }
  }
};

// A boundary star point of four faces at the origin (spokes at 0, 45, ..., 180 degrees of lengths `spokes`, sector k
// spokes[k] x spokes[k + 1] faces): the corners of sector 0 lie spokes[0] edges from it along the boundary.
SectorMesh corner_fan(const std::array<int, 5>& spokes) {
  SectorMesh s;
  for (int k = 0; k < 4; ++k) s.sector({0, 0}, 45.0 * k, 45.0 * (k + 1), spokes[static_cast<std::size_t>(k)], spokes[static_cast<std::size_t>(k) + 1]);
  return s;
}

struct Checks {
  test::ChartComparison charts;
  test::Continuity continuity;
  double spread = 0;  // largest over the star points
  int loops = 0;
};

// The Catmull-Clark faces whose two rings avoid the star points (more than `charts` of them) against their
// charts' T-spline, continuity across every interior edge, one tangent plane at each star point, one boundary loop.
// With unequal knot intervals the derivatives in the faces' own (u, v) differ across edges (no C1 check).
Checks check_surface(const TMesh& m, const TMeshSurface& s, int charts, bool equal_intervals = true) {
  Checks c;
  c.charts = test::compare_with_charts(m, s, FaceMethod::bicubic);
  c.continuity = test::continuity(m, [&](int f, double u, double v, double* o) { s.eval(f, u, v, o); });
  for (int star : s.stars()) c.spread = std::max(c.spread, tangent_plane_spread(s, star));
  const TSplineTriangulation t = tessellate(s, 1e-2);
  for (const auto& p : t.points) EXPECT_TRUE(std::isfinite(p[0] + p[1] + p[2]));
  c.loops = test::boundary_loops(t);
  EXPECT_GT(c.charts.compared, charts);
  EXPECT_LT(c.charts.position, 1e-12);
  EXPECT_LT(c.charts.derivative, 1e-11);
  EXPECT_LT(c.continuity.gap, 1e-12);
  EXPECT_LT(c.continuity.normal_angle, 1e-10);
  if (equal_intervals) {
    EXPECT_LT(c.continuity.c1, 1e-10);
  }
  EXPECT_LT(c.spread, 1e-9);
  EXPECT_EQ(c.loops, 1);
  return c;
}

// The distance from the limit point at corner vertex `corner` (of one face) to the nearest of its end-condition
// block points (the diagonal one is the clamped ends' value there).
double corner_to_block(const TMesh& m, const TMeshSurface& s, int corner) {
  for (int f = 0; f < s.num_faces(); ++f) {
    const auto c4 = s.corners(f);
    const int k = static_cast<int>(std::find(c4.begin(), c4.end(), corner) - c4.begin());
    if (k == 4) continue;
    double x[9];
    const auto o = corner_frame(k).origin;
    s.eval(f, o[0], o[1], x);
    double best = 1e300;
    EXPECT_EQ(m.vertices[static_cast<std::size_t>(corner)].block.size(), 3u);
    for (int b : m.vertices[static_cast<std::size_t>(corner)].block) {
      const auto& q = m.points[static_cast<std::size_t>(b)].xyz;
      best = std::min(best, std::hypot(x[0] - q[0], x[1] - q[1], x[2] - q[2]));
    }
    return best;
  }
  return 1e300;
}

int vertex_of(const SectorMesh& sm, std::array<double, 2> p) { return sm.ids.at({std::llround(p[0] * 1e6), std::llround(p[1] * 1e6)}); }

class StarNearCorner : public ::testing::TestWithParam<int> {};

TEST_P(StarNearCorner, GhostLayerGoesRoundTheCornerAsTheTSplinesClampedEnds) {
  const int d = GetParam();  // boundary edges from the star point to the corner
  SectorMesh sm = corner_fan({d, 7, 7, 7, d});  // corners d edges out on both sides
  const io::TsmModel model = offset_model(sm.q, 40u + static_cast<unsigned>(d));
  const TMesh& m = model.mesh;
  ASSERT_EQ(model.report.star_points, 1);
  const TMeshSurface s(m, 1);
  EXPECT_EQ(s.count(FaceMethod::star), 4);
  EXPECT_EQ(s.boundary_star_faces(), 4);
  EXPECT_EQ(s.count(FaceMethod::star) + s.count(FaceMethod::bicubic) + s.count(FaceMethod::exact), static_cast<int>(sm.q.quads.size()));
  // The corner (d, 0) of sector 0 and its face (d - 1, 0).
  const int corner = vertex_of(sm, sm.at({0, 0}, 0, 45, d, 0));
  const int corner_face = d - 1;
  const auto c4 = s.corners(corner_face);
  ASSERT_NE(std::find(c4.begin(), c4.end(), corner), c4.end());
  EXPECT_NE(s.method(corner_face), FaceMethod::exact);  // within the star point's Catmull-Clark region
  // The T-spline of sector 0 as one chart (the star point at its corner, where its rays stop as in the mesh): the
  // T-spline itself on the faces whose knot vectors stay in the sector (two faces from spoke 1 on), which hold the
  // corner for d >= 3.
  std::vector<int> sector0(static_cast<std::size_t>(7 * d));
  for (int f = 0; f < 7 * d; ++f) sector0[static_cast<std::size_t>(f)] = f;
  const TChart chart = t_spline_chart(m, sector0, 0, true);
  const TSplineSurface ts(chart.spline, 1);
  const auto st = [&](int v) {
    const TVertex& x = chart.spline.image.vertices[static_cast<std::size_t>(chart.vertex[static_cast<std::size_t>(v)])];
    return std::array<double, 2>{x.s, x.t};
  };
  double sector_position = 0, sector_derivative = 0;
  int sector_compared = 0;
  for (int j = 0; j < 7; ++j)
    for (int i = 2; i < d; ++i) {
      const int f = j * d + i;
      const auto c = s.corners(f);
      const auto p0 = st(c[0]), p1 = st(c[1]), p3 = st(c[3]);
      ++sector_compared;
      for (double u : {0.0, 0.3, 0.5, 1.0})
        for (double v : {0.0, 0.4, 1.0}) {
          double a[9], b[9];
          s.eval(f, u, v, a);
          ts.eval_first_derivatives({p0[0] + u * (p1[0] - p0[0]) + v * (p3[0] - p0[0]), p0[1] + u * (p1[1] - p0[1]) + v * (p3[1] - p0[1])}, b);
          for (int q = 0; q < 3; ++q) {
            sector_position = std::max(sector_position, std::abs(a[q] - b[q]));
            const double du = (p1[0] - p0[0]) * b[3 + q] + (p1[1] - p0[1]) * b[6 + q];
            const double dv = (p3[0] - p0[0]) * b[3 + q] + (p3[1] - p0[1]) * b[6 + q];
            sector_derivative = std::max({sector_derivative, std::abs(a[3 + q] - du), std::abs(a[6 + q] - dv)});
          }
        }
    }
  EXPECT_EQ(sector_compared, 7 * std::max(0, d - 2));
  EXPECT_LT(sector_position, 1e-12);
  EXPECT_LT(sector_derivative, 1e-11);
  // The limit point at both corners: one of the corner's three block points (the diagonal one, where both clamped
  // ends take their first point), also next to the star point (d = 1, one on either side of the star point).
  const double to_block = std::max(corner_to_block(m, s, corner), corner_to_block(m, s, vertex_of(sm, sm.at({0, 0}, 135, 180, 0, d))));
  EXPECT_LT(to_block, 1e-12);
  const Checks c = check_surface(m, s, 20);
  std::printf("boundary star %d edges from a corner: sector chart %d faces (position %.2e, derivative %.2e), 2-ring charts %d faces "
              "(position %.2e), corner to its block point %.2e; %d edges: gap %.2e, normal defect (sin) %.2e, C1 defect %.2e; "
              "tangent plane spread %.2e\n",
              d, sector_compared, sector_position, sector_derivative, c.charts.compared, c.charts.position, to_block, c.continuity.edges,
              c.continuity.gap, c.continuity.normal_angle, c.continuity.c1, c.spread);
}

INSTANTIATE_TEST_SUITE_P(Edges, StarNearCorner, ::testing::Values(1, 2, 3, 4));

// Two star points of four faces, six edges apart on one open stretch of boundary (S1's spoke 0 is S2's last
// spoke): their layers (seven edges either way) overlap on the stretch and are one layer there, which goes on
// round the sectors' corners and ends on both sides before the boundary eight edges out.
TEST(BoundaryStarPair, LayersOverlappingOnAnOpenStretchAreOneLayer) {
  SectorMesh sm = corner_fan({6, 7, 7, 7, 8});
  const std::array<double, 2> s2{6, 0};
  sm.sector(s2, -170, -100, 7, 7);
  sm.sector(s2, -100, -25, 7, 7);
  sm.sector(s2, -25, 45, 7, 7);
  const io::TsmModel model = offset_model(sm.q, 77u);
  const TMesh& m = model.mesh;
  ASSERT_EQ(model.report.star_points, 2);
  const TMeshSurface s(m, 1);
  ASSERT_EQ(s.stars().size(), 2u);
  EXPECT_EQ(s.count(FaceMethod::star), 8);
  EXPECT_EQ(s.boundary_star_faces(), 8);
  EXPECT_EQ(s.count(FaceMethod::star) + s.count(FaceMethod::bicubic) + s.count(FaceMethod::exact), static_cast<int>(sm.q.quads.size()));
  // The extended mesh: every vertex of the stretch between the star points is interior with four faces (one
  // ghost face per boundary link, shared by both layers), the star points have six, and the layer is open.
  const GhostedMesh g = ghost_boundary(m, s.stars(), 7);
  std::vector<int> faces_at(g.mesh.vertices.size(), 0);
  for (const TMeshLink& k : g.mesh.links)
    if (k.vertex >= 0 && k.face >= 0) ++faces_at[static_cast<std::size_t>(k.vertex)];
  for (int star : s.stars()) EXPECT_EQ(faces_at[static_cast<std::size_t>(star)], 6) << star;
  for (int i = 1; i < 6; ++i) {
    const int v = sm.ids.at({std::llround(i * 1e6), 0});
    EXPECT_EQ(faces_at[static_cast<std::size_t>(v)], 4) << i;
    EXPECT_GE(g.ghost[static_cast<std::size_t>(v)], 0) << i;
  }
  int unghosted_boundary = 0;
  for (std::size_t v = 0; v < m.vertices.size(); ++v) {
    bool on_boundary = false;
    for (const TMeshLink& k : m.links) on_boundary = on_boundary || (k.vertex == static_cast<int>(v) && k.face < 0);
    unghosted_boundary += on_boundary && g.ghost[v] < 0;
  }
  EXPECT_GT(unghosted_boundary, 0);
  const Checks c = check_surface(m, s, 20);
  std::printf("two boundary star points 6 edges apart: 2-ring charts %d faces (position %.2e); %d edges: gap %.2e, normal defect (sin) "
              "%.2e, C1 defect %.2e; tangent plane spread %.2e\n",
              c.charts.compared, c.charts.position, c.continuity.edges, c.continuity.gap, c.continuity.normal_angle, c.continuity.c1, c.spread);
}

// Four sectors of 2 x 2 faces: every side of the boundary has two edges and ends at corners, all within the star
// point's layer, which closes round the whole boundary; no face avoids the star point, so the checks are those of
// the limit surface: continuity, the tangent plane, the corners' block points and a watertight tessellation.
TEST(BoundaryCorner, EverySideTwoEdgesLong) {
  SectorMesh sm = corner_fan({2, 2, 2, 2, 2});
  const io::TsmModel model = offset_model(sm.q, 9u);
  const TMesh& m = model.mesh;
  const TMeshSurface s(m, 1);
  EXPECT_EQ(s.count(FaceMethod::star), 4);
  EXPECT_EQ(s.count(FaceMethod::star) + s.count(FaceMethod::bicubic), 16);
  double to_block = 0;
  int corners = 0;
  for (int v = 0; v < static_cast<int>(m.vertices.size()); ++v)
    if (m.vertices[static_cast<std::size_t>(v)].block.size() == 3) {
      to_block = std::max(to_block, corner_to_block(m, s, v));
      ++corners;
    }
  EXPECT_EQ(corners, 6);
  EXPECT_LT(to_block, 1e-12);
  const Checks c = check_surface(m, s, -1);
  EXPECT_EQ(c.charts.compared, 0);
}

// A corner in the layer whose end-condition block is not the three points of two clamped ends: one line naming it.
TEST(BoundaryCorner, RefusesACornerWithoutThreeBlockPoints) {
  SectorMesh sm = corner_fan({3, 7, 7, 7, 8});
  io::TsmModel model = offset_model(sm.q, 3u);
  const int corner = vertex_of(sm, sm.at({0, 0}, 0, 45, 3, 0));
  model.mesh.vertices[static_cast<std::size_t>(corner)].block.pop_back();
  try {
    const TMeshSurface s(model.mesh, 1);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("corner vertex " + std::to_string(corner) + " near a boundary star point has no end-condition block of three points"),
              std::string::npos)
        << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}

const std::vector<double> kGraded{1, 2, 0.5, 1.5, 1, 0.8, 1.2, 1};

// The cubic B-spline of control points d[0..3] on knots[0..7] at t in [knots[3], knots[4]] (de Boor's algorithm).
std::array<double, 4> de_boor_span(const std::array<double, 8>& knots, std::array<HomogeneousPoint, 4> d, double t) {
  for (std::size_t r = 1; r <= 3; ++r)
    for (std::size_t j = 3; j >= r; --j) {
      const double a = (t - knots[j]) / (knots[j + 4 - r] - knots[j]);
      for (std::size_t c = 0; c < 4; ++c) d[j][c] = (1 - a) * d[j - 1][c] + a * d[j][c];
    }
  return d[3];
}

TEST(BoundaryStar, GhostRowsOnUnequalIntervalsKeepTheClampedEnd) {
  // K = 2 (a regular boundary vertex) with rows of intervals 1, 2, 0.5, ... across the boundary: at each boundary
  // vertex the clamped cubic across it (knots 0, 0, 0, 0, y1, y2, ...; the block point, the vertex, the two rows
  // inside) and the cubic of the ghost, the moved vertex and the same two rows on the knots -3g, -2g, -g, 0, y1, ...
  // (g the ghost interval: the interval into the mesh at the vertex the layer was asked for) are one curve on
  // [0, y1] (de Boor for both).
  test::QuadMesh q = test::half_fan_mesh(2, 6, bump);
  test::grade_by_ring(q, {{6, 6}, {6, 6}}, kGraded);
  const io::TsmModel model = offset_model(q, 21);
  const TMesh& m = model.mesh;
  const int centre = vertex_at(m, 0, 0);
  ASSERT_GE(centre, 0);
  const std::array<int, 1> stars{centre};
  const GhostedMesh g = ghost_boundary(m, stars, 3);
  const auto h = [](const TMesh& x, int point) { return homogeneous(x.points[static_cast<std::size_t>(point)]); };
  const double y1 = kGraded[0], y2 = y1 + kGraded[1], y3 = y2 + kGraded[2], y4 = y3 + kGraded[3], gap = kGraded[0];
  const std::array<double, 8> clamped{0, 0, 0, 0, y1, y2, y3, y4}, ghosted{-3 * gap, -2 * gap, -gap, 0, y1, y2, y3, y4};
  double worst = 0, moved = 0;
  for (int x = -3; x <= 3; ++x) {
    const int v = vertex_at(m, x, 0), in1 = vertex_at(m, x, 1), in2 = vertex_at(m, x, 2);
    ASSERT_TRUE(v >= 0 && in1 >= 0 && in2 >= 0) << x;
    ASSERT_GE(g.ghost[static_cast<std::size_t>(v)], 0) << x;
    const TMeshVertex& mv = m.vertices[static_cast<std::size_t>(v)];
    const std::array<HomogeneousPoint, 4> a{h(m, mv.block.at(0)), h(m, mv.primary), h(m, m.vertices[static_cast<std::size_t>(in1)].primary),
                                            h(m, m.vertices[static_cast<std::size_t>(in2)].primary)};
    const std::array<HomogeneousPoint, 4> b{h(g.mesh, g.mesh.vertices[static_cast<std::size_t>(g.ghost[static_cast<std::size_t>(v)])].primary),
                                            h(g.mesh, g.mesh.vertices[static_cast<std::size_t>(v)].primary), a[2], a[3]};
    for (std::size_t c = 0; c < 3; ++c) moved = std::max(moved, std::abs(b[1][c] - a[1][c]));
    for (double t : {0.0, 0.2, 0.5, 0.9, 1.0}) {
      const auto p = de_boor_span(clamped, a, t * y1), r = de_boor_span(ghosted, b, t * y1);
      for (std::size_t c = 0; c < 4; ++c) worst = std::max(worst, std::abs(p[c] - r[c]));
    }
  }
  EXPECT_GT(moved, 1e-3);  // the vertices do move: the check is not of a layer that copies the rows
  EXPECT_LT(worst, 1e-13);
  std::printf("ghost rows on intervals 1, 2, 0.5, 1.5 across the boundary: clamped and ghosted cubics %.2e apart\n", worst);
}

class BoundaryStarIntervals : public ::testing::TestWithParam<int> {};

TEST_P(BoundaryStarIntervals, LoadAsOneSurfaceWithTheTSplineAwayFromTheStarPoint) {
  // Half fans of K = 4 and 5 sectors of 7 x 7 faces, every ring of faces its own interval: the star point's
  // faces and their neighbours (4 per sector) take local non-uniform subdivision of the mesh with its ghost layer;
  // every other face the T-spline (bicubic cells on their knots, read through the ghost layer at the boundary).
  const int sectors = GetParam();
  test::QuadMesh q = test::half_fan_mesh(sectors, 7, bump);
  test::grade_by_ring(q, std::vector<std::array<int, 2>>(static_cast<std::size_t>(sectors), {7, 7}), kGraded);
  const io::TsmModel model = offset_model(q, 60u + static_cast<unsigned>(sectors));
  const TMesh& m = model.mesh;
  const TMeshSurface s(m, 1);
  EXPECT_EQ(s.count(FaceMethod::crease), 4 * sectors);
  EXPECT_EQ(s.boundary_star_faces(), sectors);
  EXPECT_EQ(s.count(FaceMethod::crease) + s.count(FaceMethod::bicubic) + s.count(FaceMethod::exact), 49 * sectors);
  // The bicubic faces on the boundary (their rows across it the ghost layer's) are among those checked.
  int on_boundary = 0;
  for (int f = 0; f < s.num_faces(); ++f)
    if (s.method(f) == FaceMethod::bicubic)
      for (int v : s.corners(f)) on_boundary += point_of(m, v)[1] == 0 && std::abs(point_of(m, v)[0]) >= 4;
  EXPECT_GT(on_boundary, 0);
  const Checks c = check_surface(m, s, 15 * sectors, false);
  std::printf("boundary star of %d faces, intervals by ring: %d faces as charts (position %.2e, derivative %.2e); %d edges: gap %.2e, "
              "normal defect (sin) %.2e; tangent plane spread %.2e\n",
              sectors, c.charts.compared, c.charts.position, c.charts.derivative, c.continuity.edges, c.continuity.gap,
              c.continuity.normal_angle, c.spread);
}

INSTANTIATE_TEST_SUITE_P(Faces, BoundaryStarIntervals, ::testing::Values(4, 5));

// The Bezier patches of a boundary star point with unequal intervals: its local-subdivision faces are B-spline
// cells, and four cells that are one polynomial (where the rules were knot insertion) are one exact patch. The
// exact patches are the surface to rounding, the corner patches within the tolerance, tiling each face, C0; fewer
// patches than cells.
TEST(BoundaryStar, PatchesWithUnequalIntervalsMergeCellsOfOnePolynomial) {
  test::QuadMesh q = test::half_fan_mesh(5, 7, bump);
  test::grade_by_ring(q, std::vector<std::array<int, 2>>(5, {7, 7}), kGraded);
  const io::TsmModel model = offset_model(q, 3);
  const TMeshSurface s(model.mesh, 1);
  ASSERT_EQ(s.count(FaceMethod::crease), 20);
  const TMeshPatches p = t_mesh_patches(s);
  std::size_t cells = 0, crease_patches = 0;
  for (int f = 0; f < s.num_faces(); ++f)
    if (s.method(f) == FaceMethod::crease)
      s.crease_face(f).for_each_cell(p.levels + 1, [&](const CreaseFace::Cell&, const std::array<double, 2>&, double) { ++cells; });
  for (const FacePatch& x : p.patches) crease_patches += s.method(x.face) == FaceMethod::crease && x.exact;
  EXPECT_LT(crease_patches, cells);
  const test::PatchCheck c = test::expect_patches_hold(s, p);
  std::printf("boundary star of 5 faces, intervals by ring: %zu patches (%d corner), %d levels, the local-subdivision faces' %zu cells as %zu "
              "patches; exact patches off the surface by %.1e, corner patches by %.2e (tolerance %.2e)\n",
              p.patches.size(), p.corner_patches, p.levels, cells, crease_patches, c.exact, c.constructed, p.tolerance);
}

TEST(BoundaryStar, NearlyEqualIntervalsGiveStamsPatches) {
  // One ring of faces at 1 + 1e-9: local non-uniform subdivision with the ghost layer's crease rules on its outer
  // boundary, against Stam's exact evaluation on the same ghost layer with all intervals 1 (two independent
  // evaluations of the same limit surface as the ring tends to 1).
  std::vector<double> near(8, 1.0);
  near[1] = 1 + 1e-9;
  test::QuadMesh q = test::half_fan_mesh(5, 7, bump);
  const io::TsmModel equal = offset_model(q, 8);
  test::grade_by_ring(q, std::vector<std::array<int, 2>>(5, {7, 7}), near);
  const io::TsmModel graded = offset_model(q, 8);
  const TMeshSurface a(equal.mesh, 1), b(graded.mesh, 1);
  ASSERT_EQ(a.count(FaceMethod::star), 5);
  ASSERT_EQ(b.count(FaceMethod::crease), 20);
  double value = 0, derivative = 0;
  for (int f = 0; f < a.num_faces(); ++f) {
    // At the star point itself the parametrisation is singular: positions only.
    const auto c4 = a.corners(f);
    const int corner = static_cast<int>(std::find(c4.begin(), c4.end(), a.stars()[0]) - c4.begin());
    const std::array<double, 2> at_star = corner == 4 ? std::array<double, 2>{-1, -1} : corner_frame(corner).origin;
    for (double u : {0.0, 0.1, 0.5, 1.0})
      for (double v : {0.0, 0.3, 1.0}) {
        double x[9], y[9];
        a.eval(f, u, v, x);
        b.eval(f, u, v, y);
        for (int k = 0; k < 3; ++k) value = std::max(value, std::abs(x[k] - y[k]));
        if (std::array<double, 2>{u, v} == at_star) continue;
        for (int k = 3; k < 9; ++k) derivative = std::max(derivative, std::abs(x[k] - y[k]));
      }
  }
  EXPECT_LT(value, 1e-8);
  EXPECT_LT(derivative, 1e-7);
  std::printf("boundary star of 5 faces, one ring at 1 + 1e-9 (local subdivision) against Stam's patches: %.2e (derivatives %.2e)\n",
              value, derivative);
}

TEST(BoundaryStar, TJunctionNearItsStarPointHalvesTheIntervalsThere) {
  // A T-junction on the boundary two edges from the star point (sector 0's face [2, 3] x [0, 1] split at its
  // middle): its line is completed (t_junction_lines) across sector 0, whose knot intervals it halves.
  test::QuadMesh split = test::half_fan_mesh(4, 7, bump);
  const std::array<int, 4> f = split.quads[2];
  const int mid = static_cast<int>(split.points.size());
  split.points.push_back({2.5, 0, bump(2.5, 0)});
  split.quads.erase(split.quads.begin() + 2);
  split.t_faces.push_back({{f[0], mid, f[1], f[2], f[3]}, {0, 1, 0, 0, 0}});
  split.intervals[{f[0], mid}] = split.intervals[{mid, f[1]}] = 0.5;
  const io::TsmModel model = offset_model(split, 17);
  const TMeshSurface s(model.mesh, 1);
  ASSERT_NE(s.completed_lines(), nullptr);
  EXPECT_EQ(s.completed_lines()->lines, 1);
  EXPECT_EQ(s.boundary_star_faces(), 4);
  EXPECT_GT(s.count(FaceMethod::crease), 0);
  const Checks c = check_surface(s.mesh(), s, 40, false);
  std::printf("boundary star of 4 faces with a T-junction 2 edges away: %d faces as charts (position %.2e); %d edges: gap %.2e, normal "
              "defect (sin) %.2e; tangent plane spread %.2e\n",
              c.charts.compared, c.charts.position, c.continuity.edges, c.continuity.gap, c.continuity.normal_angle, c.spread);
}

TEST(BoundaryStar, UnequalIntervalsRoundACorner) {
  // The star point 4 edges from corners on both sides, every ring its own interval: the ghost layer goes round the
  // corners on the intervals of their two sides.
  SectorMesh sm = corner_fan({4, 7, 7, 7, 4});
  test::grade_by_ring(sm.q, {{4, 7}, {7, 7}, {7, 7}, {7, 4}}, kGraded);
  const io::TsmModel model = offset_model(sm.q, 44);
  const TMesh& m = model.mesh;
  const TMeshSurface s(m, 1);
  EXPECT_EQ(s.boundary_star_faces(), 4);
  const int corner = vertex_of(sm, sm.at({0, 0}, 0, 45, 4, 0));
  EXPECT_LT(corner_to_block(m, s, corner), 1e-12);
  const Checks c = check_surface(m, s, 20, false);
  std::printf("boundary star 4 edges from corners, intervals by ring: %d faces as charts (position %.2e); %d edges: gap %.2e, normal "
              "defect (sin) %.2e; tangent plane spread %.2e\n",
              c.charts.compared, c.charts.position, c.continuity.edges, c.continuity.gap, c.continuity.normal_angle, c.spread);
}

// A concave corner (three faces at a boundary vertex: 270 degrees, no star point) takes Rhino's ring of eight
// end-condition nodes: the T-spline is then one C2 surface across the corner's interior edges (exact faces, no
// ghost layer). With nodes in one direction only their blending functions, clamped across one side, jump across
// the interior edges at the corner (by 0.14 here): refused in one line.
TEST(BoundaryConcaveCorner, TakesARingOfEndConditionNodes) {
  const test::QuadMesh fan = test::half_fan_mesh(3, 7, bump);
  const io::TsmModel model = io::parse_tsm(tsm_text(fan), "concave.tsm");
  const TMesh& m = model.mesh;
  EXPECT_EQ(model.report.star_points, 0);
  EXPECT_EQ(m.vertices[0].block.size(), 8u);
  const TMeshSurface s(m, 1);
  EXPECT_EQ(s.count(FaceMethod::exact), 147);
  const test::Continuity c = test::continuity(m, [&](int f, double u, double v, double* o) { s.eval(f, u, v, o); });
  EXPECT_LT(c.gap, 1e-12);
  EXPECT_LT(c.normal_angle, 1e-10);
  EXPECT_LT(c.c1, 1e-10);
  EXPECT_EQ(test::boundary_loops(tessellate(s, 1e-2)), 1);
  std::printf("concave corner with a ring of end-condition nodes: %d edges, gap %.2e, normal defect (sin) %.2e, C1 defect %.2e\n", c.edges,
              c.gap, c.normal_angle, c.c1);
  TMesh one_way = m;
  TMeshVertex& corner = one_way.vertices[0];
  corner.block.resize(1);
  corner.block_dims = {0, 0, 0, 1};
  try {
    const TMeshSurface bad(one_way, 1);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("T-mesh: concave corner vertex 0 has end-condition nodes in block dims 0 0 0 1; a concave corner needs them all round"),
              std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}

}  // namespace
}  // namespace trivar
