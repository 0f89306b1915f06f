// Star points on the boundary near corners of the boundary, and two star points on one open stretch of boundary:
// Catmull-Clark on the control mesh extended by a ghost layer that goes round the corners as the tensor product
// of the clamped ends (boundary_ghosts). Known answers: the faces whose points avoid the star points are the
// T-spline of their charts (an independent Bezier extraction); the limit point at a corner is its diagonal
// end-condition block point (the clamped ends' value there); positions, normals and first derivatives agree
// across every interior edge; one tangent plane at each star point; the tessellation is watertight.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "boundary_star_checks.hpp"
#include "chart_comparison.hpp"
#include "face_continuity.hpp"
#include "star_mesh_tsm.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/tsm_format.hpp"
#include "trivar/tspline/boundary_ghosts.hpp"
#include "trivar/tspline/t_mesh_surface.hpp"
#include "trivar/tspline/t_mesh_tessellation.hpp"
#include "trivar/tspline/t_spline_surface.hpp"

namespace trivar {
namespace {

double ripple(double x, double y) { return 0.25 * std::sin(0.6 * x - 0.3) * std::cos(0.4 * y + 0.1) + 0.04 * x * y; }

constexpr double kDegree = std::numbers::pi / 180;

// Quad meshes glued from parallelogram sectors: the sector of nu x nv faces at c spanned by the unit directions at
// angles au < av (degrees); vertices at the same position are one.
struct SectorMesh {
  test::QuadMesh q;
  std::map<std::array<long long, 2>, int> ids;

  int vertex(double x, double y) {
    const auto [it, fresh] = ids.emplace(std::array<long long, 2>{std::llround(x * 1e6), std::llround(y * 1e6)}, static_cast<int>(q.points.size()));
    if (fresh) q.points.push_back({x, y, ripple(x, y)});
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

io::TsmModel model_of(const test::QuadMesh& q, unsigned seed) {
  io::TsmModel model = io::parse_tsm(tsm_text(q), "corner.tsm");
  test::offset_block_points(model.mesh, seed);
  return model;
}

struct Checks {
  test::ChartComparison charts;
  test::Continuity continuity;
  double spread = 0;  // largest over the star points
  int loops = 0;
};

// The Catmull-Clark faces whose two rings avoid the star points (more than `charts` of them) against their
// charts' T-spline, continuity across every interior edge, one tangent plane at each star point, one boundary loop.
Checks check_surface(const TMesh& m, const TMeshSurface& s, int charts) {
  Checks c;
  c.charts = test::compare_with_charts(m, s, FaceMethod::bicubic);
  c.continuity = test::continuity(m, [&](int f, double u, double v, double* o) { s.eval(f, u, v, o); });
  for (int star : s.stars()) c.spread = std::max(c.spread, test::tangent_plane_spread(s, star));
  const TSplineTriangulation t = tessellate(s, 1e-2);
  for (const auto& p : t.points) EXPECT_TRUE(std::isfinite(p[0] + p[1] + p[2]));
  c.loops = test::boundary_loops(t);
  EXPECT_GT(c.charts.compared, charts);
  EXPECT_LT(c.charts.position, 1e-12);
  EXPECT_LT(c.charts.derivative, 1e-11);
  EXPECT_LT(c.continuity.gap, 1e-12);
  EXPECT_LT(c.continuity.normal_angle, 1e-10);
  EXPECT_LT(c.continuity.c1, 1e-10);
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
  const io::TsmModel model = model_of(sm.q, 40u + static_cast<unsigned>(d));
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
  const io::TsmModel model = model_of(sm.q, 77u);
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
  const io::TsmModel model = model_of(sm.q, 9u);
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
  io::TsmModel model = model_of(sm.q, 3u);
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

}  // namespace
}  // namespace trivar
