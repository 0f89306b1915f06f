// Star points of degree 5 and 7: averaging subdivision (linear subdivision and (p - 1) / 2 averaging passes per
// step). On a regular grid its patches must be the uniform B-spline of degree p on every level, against the cardinal
// B-splines computed here by their own recursion on integer knots; on closed meshes with star points the surface
// must be continuous with one tangent plane at each star point, and where the mesh is regular away from star points
// it must meet the exact T-spline faces (charts, another code path) C^1.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "face_continuity.hpp"
#include "patch_check.hpp"
#include "fusion_cages.hpp"
#include "star_mesh_tsm.hpp"
#include "support/temp_dir.hpp"
#include "triangulation_loops.hpp"
#include "tsm_error.hpp"
#include "trivar/io/tsm_format.hpp"
#include "trivar/tspline/averaging_face.hpp"
#include "trivar/tspline/t_mesh_patches.hpp"
#include "trivar/tspline/t_mesh_surface.hpp"

namespace trivar::averaging_face_test {
namespace {

using H = std::array<double, 4>;

// The cardinal B-spline of degree p on the knots 0, 1, ..., p + 1 and its derivative, by the Cox-de Boor recursion.
std::array<double, 2> cardinal(int p, double t) {
  std::vector<double> n(static_cast<std::size_t>(p + 2), 0.0);
  for (int i = 0; i <= p; ++i) n[static_cast<std::size_t>(i)] = t >= i && t < i + 1 ? 1.0 : 0.0;
  double derivative = 0;
  for (int k = 1; k <= p; ++k) {
    if (k == p) derivative = n[0] - n[1];
    for (int i = 0; i + k <= p; ++i)
      n[static_cast<std::size_t>(i)] = ((t - i) * n[static_cast<std::size_t>(i)] + (i + k + 1 - t) * n[static_cast<std::size_t>(i + 1)]) / k;
  }
  return {n[0], derivative};
}

// A regular grid net of the face [0, 1]^2 and `rings` rings of faces round it, with vertex (x, y) at integer
// coordinates: homogeneous point (w x, w y, w z, w).
QuadNet grid_net(int rings, double (*z)(double, double), double (*w)(double, double)) {
  QuadNet n;
  const int side = 2 * rings + 2;
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i) {
      const double x = i - rings, y = j - rings, wt = w(x, y);
      n.points.push_back({wt * x, wt * y, wt * z(x, y), wt});
    }
  const auto id = [&](int i, int j) { return (j + rings) * side + i + rings; };
  n.quads.push_back({id(0, 0), id(1, 0), id(1, 1), id(0, 1)});
  for (int j = -rings; j <= rings; ++j)
    for (int i = -rings; i <= rings; ++i)
      if (i != 0 || j != 0) n.quads.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
  return n;
}

double height(double x, double y) { return 0.1 * x * x * x - 0.05 * x * y * y + 0.3 * std::sin(x + 0.5 * y); }
double weight(double x, double y) { return 1 + 0.3 * std::sin(0.7 * x - 0.4 * y) * std::cos(0.3 * y); }

// The homogeneous uniform B-spline of the grid's points at (x, y) (the face is [0, 1]^2) and its derivatives.
std::array<double, 12> grid_spline(int p, double x, double y) {
  std::array<double, 12> s{};
  const int reach = (p + 1) / 2;
  for (int j = -reach; j <= reach + 1; ++j)
    for (int i = -reach; i <= reach + 1; ++i) {
      // The control point at vertex (i, j) has the knots i - (p + 1) / 2 .. i + (p + 1) / 2.
      const auto bu = cardinal(p, x - i + (p + 1) / 2.0), bv = cardinal(p, y - j + (p + 1) / 2.0);
      const double wt = weight(i, j);
      const H pt{wt * i, wt * j, wt * height(i, j), wt};
      for (std::size_t c = 0; c < 4; ++c) {
        s[c] += bu[0] * bv[0] * pt[c];
        s[4 + c] += bu[1] * bv[0] * pt[c];
        s[8 + c] += bu[0] * bv[1] * pt[c];
      }
    }
  return s;
}

TEST(AveragingSubdivision, RegularGridIsTheUniformBSplineOfItsDegreeOnEveryLevel) {
  for (int p : {3, 5, 7}) {
    const int m = (p - 1) / 2;
    QuadNet net = grid_net(m + 1, height, weight);
    // Levels 0, 1, 2: the sub-face at corner 2, then at corner 1 of that, [1/2, 1]^2 then [3/4, 1] x [1/2, 3/4].
    std::array<double, 2> lo{0, 0};
    double size = 1, worst = 0;
    for (int level = 0; level <= 2; ++level) {
      const AveragingFace face(net, p);
      EXPECT_FALSE(face.irregular(0) || face.irregular(1) || face.irregular(2) || face.irregular(3));
      for (double u : {0.0, 0.13, 0.5, 0.77, 1.0})
        for (double v : {0.0, 0.31, 0.62, 1.0}) {
          double got[12];
          face.eval(u, v, got);
          const std::array<double, 12> want = grid_spline(p, lo[0] + size * u, lo[1] + size * v);
          for (std::size_t c = 0; c < 12; ++c) worst = std::max(worst, std::abs(got[c] - (c < 4 ? 1.0 : size) * want[c]));
        }
      const int child = level == 0 ? 2 : 1;
      net = averaging_refine(net, {child}, m, m + 1);
      size /= 2;
      lo = {lo[0] + size, lo[1] + (child == 2 ? size : 0)};
    }
    std::printf("degree %d: averaging patches on levels 0 to 2 against the uniform B-spline: %.2e\n", p, worst);
    EXPECT_LT(worst, 1e-13) << "degree " << p;
  }
}

// A cube of n x n faces per side, its points moved off the cube so that no face is planar, at degree p.
TMesh bent_cube(int n, int p, test::QuadMesh* cage = nullptr) {
  test::QuadMesh cube = test::box_mesh({n, n, n});
  for (auto& x : cube.points) x = {x[0] + 0.1 * std::sin(2 * x[1] + x[2]), x[1] + 0.08 * std::cos(3 * x[0]), x[2] + 0.05 * x[0] * x[1]};
  if (cage) *cage = cube;
  std::string text = test::tsm_text(cube);
  text.replace(text.find("degree 3"), 8, "degree " + std::to_string(p));
  return io::parse_tsm(text, "cube.tsm").mesh;
}

// The largest angle (sine) between the normals of the faces at star point `star`, each at (h, h) from its corner
// there in the face's own frame.
double normal_spread(const TMeshSurface& s, int star, double h) {
  std::vector<std::array<double, 3>> normals;
  for (int f = 0; f < s.num_faces(); ++f) {
    const std::array<int, 4> c = s.corners(f);
    for (int k = 0; k < 4; ++k)
      if (c[static_cast<std::size_t>(k)] == star) {
        const double u = k == 1 || k == 2 ? 1 - h : h, v = k >= 2 ? 1 - h : h;
        double o[9];
        s.eval(f, u, v, o);
        normals.push_back(test::unit_normal(o));
      }
  }
  double spread = 0;
  for (const auto& a : normals)
    for (const auto& b : normals)
      spread = std::max(spread, std::hypot(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]));
  return spread;
}

TEST(AveragingSubdivision, ClosedCubesOfDegreesFiveAndSeven) {
  for (int p : {5, 7}) {
    const TMesh mesh = bent_cube(3, p);
    const TMeshSurface s(mesh, 1);
    ASSERT_EQ(s.stars().size(), 8u);
    EXPECT_EQ(s.count(FaceMethod::averaging), s.num_faces());
    const auto eval = [&](int f, double u, double v, double* o) { s.eval(f, u, v, o); };
    const test::Continuity c = test::continuity(s.mesh(), eval);
    std::vector<int> all(static_cast<std::size_t>(s.num_faces()));
    for (int f = 0; f < s.num_faces(); ++f) all[static_cast<std::size_t>(f)] = f;
    const double fd = test::finite_difference_error(eval, all, {{0.3, 0.6}, {0.05, 0.9}, {0.5, 0.02}});
    double spread_coarse = 0, spread_fine = 0;
    for (int star : s.stars()) {
      spread_coarse = std::max(spread_coarse, normal_spread(s, star, std::ldexp(1.0, -8)));
      spread_fine = std::max(spread_fine, normal_spread(s, star, std::ldexp(1.0, -24)));
    }
    std::printf("degree %d cube, %d faces over %d edges: gap %.1e, normals %.1e, C1 %.1e, derivatives vs differences %.1e; "
                "normals round a star point %.1e at 2^-8, %.1e at 2^-24\n",
                p, s.num_faces(), c.edges, c.gap, c.normal_angle, c.c1, fd, spread_coarse, spread_fine);
    EXPECT_LT(c.gap, 1e-14);
    EXPECT_LT(c.normal_angle, 1e-12);
    EXPECT_LT(c.c1, 1e-12);
    EXPECT_LT(fd, 1e-7);
    // One tangent plane at each star point: the normals converge to one.
    EXPECT_LT(spread_fine, 1e-4);
    EXPECT_LT(spread_fine, spread_coarse / 100);
  }
}

TEST(AveragingSubdivision, StarPointsOfValenceThreeAndFiveJoinedByAnEdge) {
  std::string text = test::tsm_text(test::turned_edge_cube());
  text.replace(text.find("degree 3"), 8, "degree 5");
  const TMeshSurface s(io::parse_tsm(text, "turned.tsm").mesh, 1);
  int five = 0;
  for (int star : s.stars()) five += s.valence(star) == 5;
  EXPECT_GE(five, 2);
  const test::Continuity c = test::continuity(s.mesh(), [&](int f, double u, double v, double* o) { s.eval(f, u, v, o); });
  double spread = 0;
  for (int star : s.stars()) spread = std::max(spread, normal_spread(s, star, std::ldexp(1.0, -24)));
  std::printf("degree 5, star points of valence 3 and 5 joined by an edge: gap %.1e, normals %.1e, C1 %.1e; normals round a "
              "star point at 2^-24 %.1e\n", c.gap, c.normal_angle, c.c1, spread);
  EXPECT_LT(c.gap, 1e-14);
  EXPECT_LT(c.normal_angle, 1e-12);
  EXPECT_LT(c.c1, 1e-12);
  EXPECT_LT(spread, 1e-4);
}

// On a cube of 16 faces per side the faces 7 face rings and more from the star points' faces are exact (charts of
// the T-spline, which knows nothing of subdivision); the averaging faces must meet them as one spline.
TEST(AveragingSubdivision, MeetsTheExactTSplineFaces) {
  const TMeshSurface s(bent_cube(16, 5), 1);
  EXPECT_GT(s.count(FaceMethod::exact), 300);
  EXPECT_EQ(s.count(FaceMethod::exact) + s.count(FaceMethod::averaging), s.num_faces());
  const TMesh& m = s.mesh();
  double gap = 0;
  int between = 0;
  for (const TMeshLink& a : m.links) {
    if (a.face < 0 || a.opp < 0) continue;
    const TMeshLink& b = m.links[static_cast<std::size_t>(a.opp)];
    if (b.face < 0 || s.method(a.face) != FaceMethod::exact || s.method(b.face) != FaceMethod::averaging) continue;
    ++between;
    const int ka = test::side_of(m, a.face, static_cast<int>(&a - m.links.data())), kb = test::side_of(m, b.face, a.opp);
    for (double t : {0.0, 0.25, 0.5, 0.9}) {
      const auto ua = test::side_uv(ka, t), ub = test::side_uv(kb, 1 - t);
      double x[9], y[9];
      s.eval(a.face, ua[0], ua[1], x);
      s.eval(b.face, ub[0], ub[1], y);
      gap = std::max(gap, std::hypot(x[0] - y[0], x[1] - y[1], x[2] - y[2]));
    }
  }
  const test::Continuity all = test::continuity(m, [&](int f, double u, double v, double* o) { s.eval(f, u, v, o); });
  std::printf("degree 5 cube of 16 faces per side: %d exact and %d averaging faces, %d edges between them: gap %.1e; "
              "all edges: gap %.1e, normals %.1e, C1 %.1e\n",
              s.count(FaceMethod::exact), s.count(FaceMethod::averaging), between, gap, all.gap, all.normal_angle, all.c1);
  EXPECT_GT(between, 50);
  EXPECT_LT(gap, 1e-13);
  EXPECT_LT(all.gap, 1e-13);
  EXPECT_LT(all.c1, 1e-11);
}

TEST(AveragingSubdivision, WhatItDoesNotTakeIsRefused) {
  // A boundary within the face rings the rules read (an open box: Bezier end conditions have no subdivision rule).
  std::string open = test::tsm_text(test::box_mesh({3, 3, 3}, true));
  open.replace(open.find("degree 3"), 8, "degree 5");
  test::expect_surface_refusal(io::parse_tsm(open, "open.tsm").mesh, "boundary vertex");
  // Unequal knot intervals.
  std::string uneven = test::tsm_text(test::cube_mesh(3));
  uneven.replace(uneven.find("degree 3"), 8, "degree 5");
  const auto line = uneven.find("\ne ") + 1, end = uneven.find('\n', line);
  uneven.replace(end - 1, 1, "2");  // the first edge's interval 1 -> 2
  test::expect_surface_refusal(io::parse_tsm(uneven, "uneven.tsm").mesh, "knot interval");
}

// Bezier patches: each regular sub-face one exact patch of degree p, each star corner's square the interpolant;
// polynomial where every weight is 1, rational with a weight 2.
TEST(AveragingSubdivision, BezierPatchesOfDegreesFiveAndSeven) {
  for (int p : {5, 7})
    for (const bool weighted : {false, true}) {
      TMesh mesh = bent_cube(3, p);
      if (weighted) mesh.points[5].w = 2;
      const TMeshSurface s(mesh, 1);
      const TMeshPatches patches = t_mesh_patches(s);
      int corners = 0, rational = 0;
      for (const FacePatch& q : patches.patches) {
        EXPECT_EQ(q.surface.degree(0), p);
        corners += !q.exact;
        rational += q.surface.is_rational();
      }
      const test::PatchCheck c = test::expect_patches_hold(s, patches, "degree " + std::to_string(p));
      std::printf("degree %d cube%s: %zu patches (%d at star corners, %d rational), %d levels; exact patches %.1e, corner patches "
                  "%.1e (tolerance %.1e), gaps inside faces %.1e, across edges %.1e, at corner patches %.1e\n",
                  p, weighted ? " with a weight 2" : "", patches.patches.size(), corners, rational, patches.levels, c.exact, c.constructed,
                  patches.tolerance, c.inner_gap, c.edge_gap, c.corner_gap);
      EXPECT_EQ(corners, 24);  // three faces at each of the eight star points
      if (weighted)
        EXPECT_GT(rational, 0);
      else
        EXPECT_EQ(rational, 0);
    }
}

TEST(AveragingSubdivision, CommandLine) {
  const test::TempDir dir;
  test::QuadMesh cage;
  bent_cube(3, 5, &cage);
  std::string text = test::tsm_text(cage);
  text.replace(text.find("degree 3"), 8, "degree 5");
  const std::string path = dir.file("cube5.tsm");
  std::ofstream(path) << text;
  const std::string json = test::run_cli(dir, "info " + path + " --json");
  EXPECT_NE(json.find("\"faces_averaging_subdivision\": 54"), std::string::npos) << json;
  test::run_cli(dir, "convert " + path + " " + dir.file("cube5.obj"));
  const TSplineTriangulation t = test::obj_triangles(dir.file("cube5.obj"));
  EXPECT_EQ(test::boundary_loops(t), 0);  // closed
  const std::string g2 = test::run_cli(dir, "convert " + path + " " + dir.file("cube5.g2"));
  EXPECT_NE(g2.find("Bezier patches"), std::string::npos) << g2;
}

}  // namespace
}  // namespace trivar::averaging_face_test
