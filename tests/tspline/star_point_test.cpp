// T-meshes with star points (extraordinary vertices): Catmull-Clark patches against closed forms, charts
// against the global T-spline, continuity across every edge of hand-built TSM models, watertight tessellation.
#include <gtest/gtest.h>

#include <map>
#include <random>

#include "chart_comparison.hpp"
#include "face_continuity.hpp"
#include "star_mesh_tsm.hpp"
#include "tsm_error.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/tsm_format.hpp"
#include "trivar/tspline/catmull_clark_patch.hpp"
#include "trivar/tspline/t_mesh_builder.hpp"
#include "trivar/tspline/t_mesh_surface.hpp"
#include "trivar/tspline/t_mesh_tessellation.hpp"
#include "trivar/tspline/t_spline_surface.hpp"

namespace trivar {
namespace {

using P3 = std::array<double, 3>;

std::vector<P3> random_points(int n, unsigned seed) {
  std::mt19937 g(seed);
  std::uniform_real_distribution<double> d(-1, 1);
  std::vector<P3> p(static_cast<std::size_t>(n));
  for (auto& x : p) x = {d(g), d(g), d(g)};
  return p;
}

TEST(CatmullClark, ValenceFourIsTheUniformBicubicPatchAtEveryLevel) {
  const auto p = random_points(16, 7);
  const CatmullClarkPatch& cc = catmull_clark_patch(4);
  const auto g = regular_grid(p);
  for (double u : {0.0, 1e-9, 0.003, 0.26, 0.5, 0.77, 1.0})
    for (double v : {1e-7, 0.1, 0.49, 0.5, 1.0}) {
      double a[9], b[9];
      cc.eval(p, u, v, a);
      eval_uniform_bicubic(g, u, v, b);
      // Derivatives at subdivision level j carry the rounding of the subdivided points times 2^j; relative to the
      // limit point those shrink like lambda^j = 2^-j for valence 4, so the derivatives stay exact to rounding.
      for (int c = 0; c < 9; ++c) EXPECT_NEAR(a[c], b[c], 1e-12 * (c < 3 ? 1 : 10)) << u << ' ' << v << ' ' << c;
    }
}

double dist(const P3& a, const double* b) { return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]); }

TEST(CatmullClark, ApproachesTheLimitPointOfHalsteadAtTheStarPoint) {
  for (int n : {3, 5, 6, 8}) {
    const auto p = random_points(2 * n + 8, static_cast<unsigned>(n));
    const CatmullClarkPatch& cc = catmull_clark_patch(n);
    const P3 x = cc.limit_point(p);
    double a[9];
    cc.eval(p, 0, 0, a);
    EXPECT_LT(dist(x, a), 1e-15);
    double prev = 1;
    for (double t : {1e-2, 1e-4, 1e-8, 1e-12}) {
      cc.eval(p, t, 0.5 * t, a);
      const double d = dist(x, a);
      EXPECT_LT(d, prev) << n << ' ' << t;
      prev = d;
    }
    EXPECT_LT(prev, 1e-6) << n;
    // First derivatives against central differences, away from and close to the star point.
    for (const auto& [u, v] : std::vector<std::pair<double, double>>{{0.3, 0.2}, {0.7, 0.9}, {0.01, 0.02}, {1e-4, 3e-5}}) {
      const double h = 1e-4 * std::min(u, v);
      double d[9], up[9], um[9], vp[9], vm[9];
      cc.eval(p, u, v, d);
      cc.eval(p, u + h, v, up);
      cc.eval(p, u - h, v, um);
      cc.eval(p, u, v + h, vp);
      cc.eval(p, u, v - h, vm);
      double scale = 0;
      for (int c = 3; c < 9; ++c) scale = std::max(scale, std::abs(d[c]));
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(d[3 + c], (up[c] - um[c]) / (2 * h), 1e-6 * scale) << n << ' ' << u << ' ' << v;
        EXPECT_NEAR(d[6 + c], (vp[c] - vm[c]) / (2 * h), 1e-6 * scale) << n << ' ' << u << ' ' << v;
      }
    }
    // A planar control net gives a planar patch, and an affine map of the net maps the patch.
    auto q = p;
    for (auto& y : q) y = {2 * y[0] + y[1] + 3, -y[0] + 0.5 * y[1] - 1, 0.25 * y[2]};
    double b[9];
    for (double u : {0.01, 0.3, 0.9}) {
      cc.eval(p, u, 0.7 * u, a);
      cc.eval(q, u, 0.7 * u, b);
      EXPECT_NEAR(b[0], 2 * a[0] + a[1] + 3, 1e-12);
      EXPECT_NEAR(b[1], -a[0] + 0.5 * a[1] - 1, 1e-12);
      EXPECT_NEAR(b[2], 0.25 * a[2], 1e-12);
    }
  }
}

void expect_watertight_closed(const TSplineTriangulation& t, bool closed) {
  std::map<std::array<int, 2>, int> use;
  for (const auto& tri : t.triangles)
    for (int k = 0; k < 3; ++k) ++use[{tri[static_cast<std::size_t>(k)], tri[static_cast<std::size_t>((k + 1) % 3)]}];
  int boundary = 0, twice = 0;
  for (const auto& [e, n] : use) {
    twice += n != 1;
    if (!use.count({e[1], e[0]})) ++boundary;
  }
  EXPECT_EQ(twice, 0) << "edges used twice in the same direction";
  if (closed) {
    EXPECT_EQ(boundary, 0);
    // Euler characteristic of a sphere.
    EXPECT_EQ(static_cast<long>(t.points.size()) - static_cast<long>(use.size() / 2) + static_cast<long>(t.triangles.size()), 2);
  }
}

TEST(StarPoints, ClosedCubeOfEightValenceThreeStarPoints) {
  const io::TsmModel model = io::parse_tsm(tsm_text(test::cube_mesh(3)), "cube.tsm");
  EXPECT_EQ(model.report.star_points, 8);
  EXPECT_TRUE(model.spline.image.faces.empty());  // no global (s, t)
  const TMeshSurface s(model.mesh);
  EXPECT_EQ(s.count(FaceMethod::star), 24);
  EXPECT_EQ(s.count(FaceMethod::bicubic), 30);
  EXPECT_EQ(s.count(FaceMethod::exact), 0);
  for (int v : s.stars()) EXPECT_EQ(s.valence(v), 3);
  // The centre face of each side: its 4 x 4 control points are that side's flat, evenly spaced grid, so the
  // patch is the flat square [-1/3, 1/3]^2 on the side (linear precision of uniform B-splines).
  int centres = 0;
  for (int f = 0; f < s.num_faces(); ++f) {
    const auto c = s.corners(f);
    double mid[3] = {0, 0, 0};
    for (int v : c)
      for (int k = 0; k < 3; ++k) mid[k] += 0.25 * model.mesh.points[static_cast<std::size_t>(v)].xyz[static_cast<std::size_t>(k)];
    if (std::abs(std::abs(mid[0]) + std::abs(mid[1]) + std::abs(mid[2]) - 1) > 1e-12) continue;
    ++centres;
    const auto& p0 = model.mesh.points[static_cast<std::size_t>(c[0])].xyz;
    const auto& p1 = model.mesh.points[static_cast<std::size_t>(c[1])].xyz;
    const auto& p3 = model.mesh.points[static_cast<std::size_t>(c[3])].xyz;
    for (double u : {0.0, 0.3, 1.0})
      for (double v : {0.0, 0.6, 1.0}) {
        double o[9];
        s.eval(f, u, v, o);
        for (int k = 0; k < 3; ++k)
          EXPECT_NEAR(o[k], p0[static_cast<std::size_t>(k)] + u * (p1[static_cast<std::size_t>(k)] - p0[static_cast<std::size_t>(k)]) + v * (p3[static_cast<std::size_t>(k)] - p0[static_cast<std::size_t>(k)]), 1e-14);
      }
  }
  EXPECT_EQ(centres, 6);
  const test::Continuity c = test::continuity(s.mesh(), [&](int f, double u, double v, double* o) { s.eval(f, u, v, o); });
  EXPECT_EQ(c.edges, 108);
  std::printf("cube: %d edges, position gap %.2e, normal defect (sin) %.2e, C1 defect %.2e\n", c.edges, c.gap,
              c.normal_angle, c.c1);
  EXPECT_LT(c.gap, 1e-14);
  EXPECT_LT(c.normal_angle, 1e-12);
  EXPECT_LT(c.c1, 1e-12);
  // G1 at the star points: the limit normals of the three faces agree, and the faces' normals approach it.
  double worst_g1 = 0;
  for (int f = 0; f < s.num_faces(); ++f) {
    if (s.method(f) != FaceMethod::star) continue;
    double o[9], near[9];
    const auto corners = s.corners(f);
    int k = 0;
    while (std::find(s.stars().begin(), s.stars().end(), corners[static_cast<std::size_t>(k)]) == s.stars().end()) ++k;
    const std::array<std::array<double, 2>, 4> at{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
    const auto& x = at[static_cast<std::size_t>(k)];
    s.eval(f, x[0], x[1], o);
    s.eval(f, std::abs(x[0] - 1e-6), std::abs(x[1] - 1e-6), near);
    const P3 n0 = test::unit_normal(o), n1 = test::unit_normal(near);
    // By symmetry the cube corner's normal is (+-1, +-1, +-1) / sqrt 3.
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(std::abs(n0[static_cast<std::size_t>(j)]), 1 / std::sqrt(3.0), 1e-12);
    const double angle = std::acos(std::min(1.0, n0[0] * n1[0] + n0[1] * n1[1] + n0[2] * n1[2]));
    EXPECT_LT(angle, 1e-3);
    worst_g1 = std::max(worst_g1, angle);
  }
  std::printf("cube: normal 1e-6 from a star point off its limit normal by %.2e rad\n", worst_g1);
  const TSplineTriangulation t = tessellate(s, 1e-3);
  expect_watertight_closed(t, true);
}

double height(double x, double y) { return 0.05 * x * x - 0.03 * x * y + 0.2 * std::sin(0.4 * y); }

// Exact and Catmull-Clark faces of a fan meet as one C2 surface (an exact face with uniform knots is the
// uniform bicubic patch of its 4 x 4 control points).
void expect_one_smooth_surface(const TMeshSurface& s, const char* name) {
  const test::Continuity c = test::continuity(s.mesh(), [&](int f, double u, double v, double* o) { s.eval(f, u, v, o); });
  EXPECT_LT(c.gap, 1e-12) << name;
  EXPECT_LT(c.normal_angle, 1e-10) << name;
  EXPECT_LT(c.c1, 1e-10) << name;
  std::printf("%s: %d edges, position gap %.2e, normal defect (sin) %.2e, C1 defect %.2e\n", name, c.edges, c.gap,
              c.normal_angle, c.c1);
}

TEST(StarPoints, PlanarFanAroundAValenceFiveStarPoint) {
  const io::TsmModel model = io::parse_tsm(tsm_text(test::fan_mesh(5, 8, height)), "fan.tsm");
  EXPECT_EQ(model.report.star_points, 1);
  const TMeshSurface s(model.mesh, 1);
  EXPECT_EQ(s.count(FaceMethod::star), 5);
  // Within 5 face rings of the star point (max(i, j) < 5 in each sector): Catmull-Clark; beyond: exact.
  EXPECT_EQ(s.count(FaceMethod::bicubic), 5 * 25 - 5);
  EXPECT_EQ(s.count(FaceMethod::exact), 5 * 39);
  expect_one_smooth_surface(s, "valence-5 fan");
  const TSplineTriangulation t = tessellate(s, 1e-2);
  expect_watertight_closed(t, false);
  for (const auto& p : t.points) ASSERT_TRUE(std::isfinite(p[0] + p[1] + p[2]));  // the boundary too (end conditions)
  EXPECT_GT(t.triangles.size(), 500u);
}

// T-meshes without star points through the charts, face by face against the global T-spline: T-junctions,
// Bezier end-condition blocks, rational points; the second has a coarse quarter of 2 x 2 faces beside fine ones,
// where knot vectors reach further in face rings.
std::vector<std::vector<KnotSegment>> chart_test_meshes() {
  std::vector<KnotSegment> a;
  for (int i = 0; i <= 7; ++i) {
    a.push_back({{0.0, double(i)}, {7.0, double(i)}});
    a.push_back({{double(i), 0.0}, {double(i), i == 3 ? 3.0 : 7.0}});
  }
  a.push_back({{2.5, 4.0}, {2.5, 7.0}});
  std::vector<KnotSegment> b;
  for (int i = 0; i <= 12; ++i) {
    const bool odd = i % 2 == 1;
    b.push_back({{0.0, double(i)}, {odd ? 4.0 : 12.0, double(i)}});
    b.push_back({{double(i), 0.0}, {double(i), odd ? 4.0 : 12.0}});
  }
  return {a, b};
}

TEST(StarPoints, ChartsGiveTheGlobalTSplineOnEveryFace) {
  for (const auto& g : chart_test_meshes()) {
  const TSpline ts = t_spline_from_segments({3, 3}, g, [](double s, double t, int a, int b) {
    return RationalPoint{{s + 0.1 * a, t + 0.1 * b, std::sin(s + t)}, 1.0 + 0.01 * s};
  });
  std::ostringstream os;
  io::write_tsm(os, ts);
  const io::TsmModel model = io::parse_tsm(os.str(), "t.tsm");
  const TSplineSurface global(model.spline);
  const TChart chart = t_spline_chart(model.mesh, {}, 0, true);
  const TMeshSurface s(model.mesh);
  EXPECT_EQ(s.count(FaceMethod::exact), static_cast<int>(model.spline.image.faces.size()));
  double worst = 0;
  for (int f = 0; f < s.num_faces(); ++f) {
    if (s.method(f) == FaceMethod::none) continue;
    const auto c = s.corners(f);
    const auto st = [&](int v) {
      const TVertex& x = chart.spline.image.vertices[static_cast<std::size_t>(chart.vertex[static_cast<std::size_t>(v)])];
      return std::array<double, 2>{x.s, x.t};
    };
    const auto p0 = st(c[0]), p1 = st(c[1]), p3 = st(c[3]);
    for (double u : {0.13, 0.5, 0.87})
      for (double v : {0.21, 0.5, 0.79}) {
        double a[9], b[9];
        s.eval(f, u, v, a);
        const Param<2> x{p0[0] + u * (p1[0] - p0[0]) + v * (p3[0] - p0[0]), p0[1] + u * (p1[1] - p0[1]) + v * (p3[1] - p0[1])};
        global.eval_first_derivatives(x, b);
        for (int k = 0; k < 3; ++k) {
          worst = std::max(worst, std::abs(a[k] - b[k]));
          const double du = (p1[0] - p0[0]) * b[3 + k] + (p1[1] - p0[1]) * b[6 + k];
          const double dv = (p3[0] - p0[0]) * b[3 + k] + (p3[1] - p0[1]) * b[6 + k];
          worst = std::max({worst, std::abs(a[3 + k] - du), std::abs(a[6 + k] - dv)});
        }
      }
  }
  EXPECT_LT(worst, 1e-12);
  // T-junction faces pass their long side's samples across: still no T-vertex in the triangulation.
  expect_watertight_closed(tessellate(s, 1e-2), false);
  }
}

// The mesh written back as TSM (every slot in place) reads as the same surface.
TEST(StarPoints, TsmRoundTripOfTheMesh) {
  for (const std::string& text : {tsm_text(test::cube_mesh(3)), tsm_text(test::fan_mesh(5, 8, height))}) {
    const io::TsmModel a = io::parse_tsm(text, "a.tsm");
    std::ostringstream out;
    io::write_tsm(out, a.mesh);
    const io::TsmModel b = io::parse_tsm(out.str(), "b.tsm");
    EXPECT_EQ(b.report.star_points, a.report.star_points);
    EXPECT_EQ(b.report.repeated_knot_nodes, a.report.repeated_knot_nodes);
    const TMeshSurface sa(a.mesh), sb(b.mesh);
    ASSERT_EQ(sa.num_faces(), sb.num_faces());
    for (int f = 0; f < sa.num_faces(); ++f) {
      ASSERT_EQ(sa.method(f), sb.method(f));
      for (double u : {0.0, 0.4, 1.0}) {
        double x[9], y[9];
        sa.eval(f, u, 0.7, x);
        sb.eval(f, u, 0.7, y);
        for (int c = 0; c < 9; ++c) ASSERT_EQ(x[c], y[c]) << f;
      }
    }
  }
}

void expect_error(const std::string& text, const std::string& fragment) {
  try {
    const io::TsmModel m = io::parse_tsm(text, "bad.tsm");
    const TMeshSurface s(m.mesh);
    ADD_FAILURE() << "no error for " << fragment;
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(fragment), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}

// A star point 2 to 7 faces from a Bezier boundary: the boundary near it gets the ghost layer of its end
// condition (boundary_ghosts), so the faces within 5 rings of the star point are Catmull-Clark faces of the
// extended mesh (bicubic: the T-spline itself, also where their 4 x 4 points hold ghost rows), the rest exact
// in charts; one smooth surface, the bicubic faces equal to their charts where those exist.
TEST(StarPoints, FacesNearStarPointsAndTheBoundaryReadTheGhostLayer) {
  for (int rings : {2, 4, 7}) {
    const io::TsmModel model = io::parse_tsm(tsm_text(test::fan_mesh(5, rings, height)), "fan.tsm");
    const TMeshSurface s(model.mesh, 1);
    const int within = std::min(rings, 5);
    EXPECT_EQ(s.count(FaceMethod::star), 5);
    EXPECT_EQ(s.count(FaceMethod::bicubic), 5 * within * within - 5) << rings;
    EXPECT_EQ(s.count(FaceMethod::exact), 5 * (rings * rings - within * within)) << rings;
    const test::ChartComparison cmp = test::compare_with_charts(model.mesh, s, FaceMethod::bicubic);
    EXPECT_EQ(cmp.compared > 0, rings > 2) << rings;
    EXPECT_LT(cmp.position, 1e-12) << rings;
    EXPECT_LT(cmp.derivative, 1e-11) << rings;
    char name[96];
    std::snprintf(name, sizeof name, "valence-5 fan, %d faces to the boundary (%d bicubic faces as charts, %.1e)", rings, cmp.compared, cmp.position);
    expect_one_smooth_surface(s, name);
  }
}

// Star points inside the mesh place a ghost layer over the boundary near them only where its vertices have their
// end-condition nodes: on an open box whose rim has none at six vertices the layer leaves that run out; the box of
// 7 faces per side loads as without a layer (its faces there in charts), the box of 5 is refused in one line
// naming the face and the boundary vertex.
TEST(StarPoints, TheGhostLayerNeedsTheBoundarysEndConditionNodes) {
  for (int n : {5, 7}) {
    const test::QuadMesh box = test::box_mesh({n, n, n}, true);
    TMesh m = io::parse_tsm(tsm_text(box), "box.tsm").mesh;
    int cleared = 0;
    for (std::size_t v = 0; v < box.points.size(); ++v)
      if (box.points[v][2] < -1 + 1e-9 && std::abs(box.points[v][0] + 1 - 4.0 / n) < 2.2 / n) {  // three columns, front and back
        m.vertices[v].block.clear();
        m.vertices[v].block_dims = {};
        ++cleared;
      }
    ASSERT_EQ(cleared, 6);
    if (n == 5) {
      test::expect_surface_refusal(m, "is within 2 rings; the Catmull-Clark evaluation around star points needs none");
      continue;
    }
    const TMeshSurface s(m, 1);
    EXPECT_GT(s.count(FaceMethod::exact), 0);
    expect_one_smooth_surface(s, "open box of 7 faces, six rim vertices without end-condition nodes");
  }
}

// Unequal knot intervals near a star point: in the valence-5 fan of 8 x 8 faces per sector, the strip of edges
// between the sector rows r and r + 1 (across sector 0 and on into sector 4) gets interval 2.
// The strip lies beyond the star point's three rings (r >= 4), so the star point keeps the uniform rules and the
// faces within 5 rings whose two rings see the strip are bicubic B-spline cells on their unequal knots.
// Each way the surface is one smooth surface (positions and normals; face-local derivatives differ by the ratio
// of the intervals), so the B-spline cells meet the T-spline of the charts beyond exactly.
TEST(StarPoints, UnequalIntervalsNearAStarPoint) {
  const auto strip = [](int row) {
    io::TsmModel model = io::parse_tsm(tsm_text(test::fan_mesh(5, 8, height)), "fan.tsm");
    TMesh& m = model.mesh;
    const double c = std::cos(2 * std::numbers::pi / 5), s = std::sin(2 * std::numbers::pi / 5);
    // Sector coordinates of a point in sector 0 (axes 0 and 72 degrees) and in sector 4 (axes 288 and 0 degrees).
    const auto sector0 = [&](const std::array<double, 3>& x) { return std::array<double, 2>{x[0] - x[1] * c / s, x[1] / s}; };
    const auto sector4 = [&](const std::array<double, 3>& x) { return std::array<double, 2>{-x[1] / s, x[0] + x[1] * c / s}; };
    const auto near = [](double a, double b) { return std::abs(a - b) < 1e-9; };
    int changed = 0;
    for (std::size_t l = 0; l < m.links.size(); ++l) {
      const TMeshLink& k = m.links[l];
      if (k.vertex < 0 || static_cast<int>(l) > k.opp) continue;
      const auto& p = m.points[static_cast<std::size_t>(m.vertices[static_cast<std::size_t>(k.vertex)].primary)].xyz;
      const auto& q = m.points[static_cast<std::size_t>(m.vertices[static_cast<std::size_t>(m.links[static_cast<std::size_t>(k.opp)].vertex)].primary)].xyz;
      const auto a0 = sector0(p), b0 = sector0(q), a4 = sector4(p), b4 = sector4(q);
      const bool in0 = near(a0[1], b0[1]) && a0[1] > -1e-9 && near(std::min(a0[0], b0[0]), row) && near(std::max(a0[0], b0[0]), row + 1);
      const bool in4 = near(a4[0], b4[0]) && a4[0] > -1e-9 && near(std::min(a4[1], b4[1]), row) && near(std::max(a4[1], b4[1]), row + 1);
      if (in0 || in4) {
        m.intervals[static_cast<std::size_t>(k.edge)] = 2;
        ++changed;
      }
    }
    EXPECT_EQ(changed, 17);  // 9 edges across sector 0, 8 more across sector 4
    return m;
  };
  for (int row : {7, 6, 5, 4}) {
    const TMeshSurface s(strip(row), 1);
    EXPECT_EQ(s.count(FaceMethod::star), 5);
    EXPECT_EQ(s.count(FaceMethod::bicubic), 5 * 25 - 5);
    const test::Continuity c = test::continuity(s.mesh(), [&](int f, double u, double v, double* o) { s.eval(f, u, v, o); });
    EXPECT_LT(c.gap, 1e-12) << row;
    EXPECT_LT(c.normal_angle, 1e-10) << row;
    std::printf("valence-5 fan, interval 2 between rows %d and %d: %d Catmull-Clark faces, position gap %.2e, normal "
                "defect (sin) %.2e\n", row, row + 1, s.count(FaceMethod::bicubic) + s.count(FaceMethod::star), c.gap,
                c.normal_angle);
  }
}

TEST(StarPoints, WhatTheCatmullClarkRegionDoesNotHoldIsRefused) {
  // Unequal knot intervals (faces with several star corners: subdivided_face_test.cpp).
  std::string uneven = tsm_text(test::cube_mesh(3));
  const auto line = uneven.find("\ne ") + 1, end = uneven.find('\n', line);
  uneven.replace(end - 1, 1, "2");  // the first edge's interval 1 -> 2
  expect_error(uneven, "knot interval");
}

// A star point on the boundary (four sectors of the valence-5 fan: the origin a boundary vertex with four faces, 360
// degrees) loads through its ghost layer (tests/tspline/boundary_star_test.cpp). T-junctions (split edges of
// interval 1/2) in the ring of faces 3 from the star point: their neighbours within 3 rings need uniform quads
// within 2 rings, and no chart without the star point holds their knot vectors, so their lines are completed.
TEST(StarPoints, TJunctionsNearAStarPoint) {
  test::QuadMesh open = test::fan_mesh(5, 8, height);
  open.quads.resize(4 * 64);
  std::vector<int> used(open.points.size(), -1);
  std::vector<std::array<double, 3>> points;
  for (auto& q : open.quads)
    for (int& v : q) {
      if (used[static_cast<std::size_t>(v)] < 0) {
        used[static_cast<std::size_t>(v)] = static_cast<int>(points.size());
        points.push_back(open.points[static_cast<std::size_t>(v)]);
      }
      v = used[static_cast<std::size_t>(v)];
    }
  open.points = std::move(points);
  const io::TsmModel boundary_star = io::parse_tsm(tsm_text(open), "open.tsm");
  EXPECT_EQ(TMeshSurface(boundary_star.mesh, 1).boundary_star_faces(), 4);
  // Within 3 face rings of the star point the T-junctions' lines are completed first (t_junction_lines), here to the
  // fan's boundary: one surface, continuous with one tangent plane across every edge.
  const TMeshSurface near(io::parse_tsm(tsm_text(test::fan_mesh_with_t_junctions(5, 8, 3, 1, 3, height)), "near.tsm").mesh, 1);
  ASSERT_NE(near.completed_lines(), nullptr);
  EXPECT_EQ(near.completed_lines()->lines, 2);
  const test::Continuity c = test::continuity(near.mesh(), [&](int f, double u, double v, double* o) { near.eval(f, u, v, o); });
  EXPECT_LT(c.gap, 1e-12);
  EXPECT_LT(c.normal_angle, 1e-9);
  // Two rings further out the T-junctions are faces of charts without the star point: the mesh loads.
  const io::TsmModel far = io::parse_tsm(tsm_text(test::fan_mesh_with_t_junctions(5, 8, 6, 2, 5, height)), "far.tsm");
  const TMeshSurface s(far.mesh, 1);
  EXPECT_EQ(s.count(FaceMethod::star), 5);
}

}  // namespace
}  // namespace trivar

