// Global non-uniform Catmull-Clark steps (non_uniform_subdivision): the surface after forced steps against the
// surface without them (uniform Catmull-Clark by Stam's method, the T-spline in charts, NonUniformStar on the
// star points' own sectors), against OpenSubdiv's uniform Catmull-Clark limit surface, and a cage whose star
// points are too close for NonUniformStar without the steps.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>
#include <vector>

#include "face_continuity.hpp"
#include "osd_reference.hpp"
#include "star_mesh_tsm.hpp"
#include "triangulation_loops.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/tsm_format.hpp"
#include "trivar/tspline/non_uniform_subdivision.hpp"
#include "trivar/tspline/t_mesh_surface.hpp"
#include "trivar/tspline/t_mesh_tessellation.hpp"

namespace trivar {
namespace {

// A cube cage of n x n faces per side with its points moved off the cube (no symmetry hides a wrong frame) and
// knot interval `wide` on the strip of faces round the box between x grid lines `strip` and strip + 1.
TMesh stepped_box(int n, int strip, double wide) {
  test::QuadMesh q = test::cube_mesh(n);
  for (auto& p : q.points) {
    const auto r = p;
    p = {r[0] + 0.05 * std::sin(2.1 * r[1] + 0.4 * r[2]), r[1] + 0.04 * std::cos(1.7 * r[2] - 0.3 * r[0]),
         r[2] + 0.06 * std::sin(1.3 * r[0] + 0.9 * r[1])};
  }
  const test::QuadMesh grid = test::cube_mesh(n);  // the grid positions, before the points moved
  const auto gx = [&](int v) { return static_cast<int>(std::lround((grid.points[static_cast<std::size_t>(v)][0] + 1) * n / 2)); };
  for (const auto& f : q.quads)
    for (int k = 0; k < 4; ++k) {
      const int a = f[static_cast<std::size_t>(k)], b = f[static_cast<std::size_t>((k + 1) % 4)];
      if (std::min(gx(a), gx(b)) == strip && std::max(gx(a), gx(b)) == strip + 1) q.intervals[{a, b}] = wide;
    }
  return io::parse_tsm(test::tsm_text(q), "stepped_box.tsm").mesh;
}

// Sample points of a face: a 4 x 4 grid with its corners, and points 2^-7 .. 1e-3 from each corner.
std::vector<std::array<double, 2>> stepped_samples() {
  std::vector<std::array<double, 2>> uv;
  for (double u : {0.0, 0.3, 0.65, 1.0})
    for (double v : {0.0, 0.4, 0.75, 1.0}) uv.push_back({u, v});
  for (double a : {0.0, 1.0})
    for (double b : {0.0, 1.0})
      for (const auto& n : {std::array<double, 2>{1.0 / 128, 1.0 / 256}, {1e-3, 0.5e-3}, {0.3, 1e-3}}) uv.push_back({a == 0 ? n[0] : 1 - n[0], b == 0 ? n[1] : 1 - n[1]});
  return uv;
}

struct StepDeviation {
  double position = 0, derivative = 0;  // relative to the derivatives' size
};

// Surface `a` (the mesh as given) against `b` (after global steps, evaluated on the faces as given).
StepDeviation step_deviation(const TMeshSurface& a, const TMeshSurface& b, const std::vector<int>& faces) {
  StepDeviation d;
  for (int f : faces)
    for (const auto& [u, v] : stepped_samples()) {
      double x[9], y[9];
      a.eval(f, u, v, x);
      b.eval_source(f, u, v, y);
      d.position = std::max(d.position, std::hypot(x[0] - y[0], x[1] - y[1], x[2] - y[2]));
      if ((u == 0 || u == 1) && (v == 0 || v == 1)) continue;  // at a star corner the derivatives are directions
      const double size = std::max({std::hypot(x[3], x[4], x[5]), std::hypot(x[6], x[7], x[8]), 1e-300});
      for (int k = 3; k < 9; ++k) d.derivative = std::max(d.derivative, std::abs(x[k] - y[k]) / size);
    }
  return d;
}

std::vector<int> all_faces(const TMeshSurface& s) {
  std::vector<int> f(static_cast<std::size_t>(s.num_faces()));
  for (int i = 0; i < s.num_faces(); ++i) f[static_cast<std::size_t>(i)] = i;
  return f;
}

// Equal intervals: the steps are uniform Catmull-Clark steps, the surface (Stam's patches, one local step at the
// faces with several star corners) does not change, and it is OpenSubdiv's.
TEST(GlobalNurccStep, EqualIntervalsLeaveTheSurfaceUnchanged) {
  const TMesh mesh = stepped_box(3, 1, 1.0);
  const TMeshSurface s(mesh, 1);
  EXPECT_EQ(s.global_steps(), 0);  // close star points, equal intervals: no steps needed
  EXPECT_EQ(s.count(FaceMethod::star), 24);
  const TMeshSurface s1(mesh, 1, 1), s2(mesh, 1, 2);
  ASSERT_EQ(s1.num_faces(), 4 * 54);
  ASSERT_EQ(s2.num_faces(), 16 * 54);
  EXPECT_EQ(s2.source_face(16 * 7 + 5), 7);
  EXPECT_EQ(s2.source_mesh().faces.size(), 54u);
  const StepDeviation d1 = step_deviation(s, s1, all_faces(s)), d2 = step_deviation(s, s2, all_faces(s));
  EXPECT_LT(d1.position, 1e-13);
  EXPECT_LT(d1.derivative, 1e-11);
  EXPECT_LT(d2.position, 1e-13);
  EXPECT_LT(d2.derivative, 1e-11);
  // OpenSubdiv on the mesh as given (its face frames are trivar's: corners from the first corner link).
  test::PolyMesh p;
  for (const TMeshVertex& v : mesh.vertices) p.points.push_back(mesh.points[static_cast<std::size_t>(v.primary)].xyz);
  for (int f = 0; f < s.num_faces(); ++f) {
    const auto c = s.corners(f);
    p.faces.push_back({c.begin(), c.end()});
  }
  const test::OsdLimitSurface osd(p);
  double osd_position = 0, osd_derivative = 0;
  for (int f = 0; f < s.num_faces(); ++f)
    for (const auto& [u, v] : stepped_samples()) {
      double y[9];
      s2.eval_source(f, u, v, y);
      const test::LimitSample o = osd.eval(f, u, v);
      osd_position = std::max(osd_position, std::hypot(y[0] - o.p[0], y[1] - o.p[1], y[2] - o.p[2]));
      const bool corner = (u == 0 || u == 1) && (v == 0 || v == 1);  // the star corners' parametrisation is singular
      if (!corner)
        osd_derivative = std::max({osd_derivative, std::hypot(y[3] - o.du[0], y[4] - o.du[1], y[5] - o.du[2]),
                                   std::hypot(y[6] - o.dv[0], y[7] - o.dv[1], y[8] - o.dv[2])});
    }
  EXPECT_LT(osd_position, 1e-12);
  EXPECT_LT(osd_derivative, 1e-10);
  std::printf("box 3 x 3, equal intervals: 1 step %.1e / %.1e, 2 steps %.1e / %.1e (position / relative derivatives); "
              "2 steps against OpenSubdiv %.1e / %.1e\n", d1.position, d1.derivative, d2.position, d2.derivative, osd_position, osd_derivative);
}

// Unequal intervals, star points 7 edges apart: NonUniformStar evaluates the mesh as given, and the forced step
// must give the same surface on every face (the step's rules are NonUniformStar's first level at the star
// points and exact knot insertion elsewhere, where the faces are the T-spline in charts of the mesh as given).
TEST(GlobalNurccStep, UnequalIntervalsFarApartMatchNonUniformStar) {
  // The strip 3 edges from every star point (after the step 6, beyond the three rings: uniform Stam patches there
  // and bicubic cells on the unequal knots), or 1 from four of them and 5 from the others (after the step 2, still
  // non-uniform, and 10). The faces' sides are compared too: where the intervals jump, each face's derivatives
  // are its own (one-sided).
  for (const auto& [strip, wide, nurcc_stars, stepped_nurcc] : {std::tuple{3, 1.02, 8, 0}, std::tuple{1, 1.5, 4, 4}}) {
    const TMesh mesh = stepped_box(7, strip, wide);
    const TMeshSurface s(mesh, 1);
    EXPECT_EQ(s.global_steps(), 0);
    EXPECT_EQ(s.non_uniform_stars(), nurcc_stars);
    const TMeshSurface s1(mesh, 1, 1);
    EXPECT_EQ(s1.non_uniform_stars(), stepped_nurcc);
    std::vector<int> nurcc, other;
    for (int f = 0; f < s.num_faces(); ++f) (s.method(f) == FaceMethod::non_uniform ? nurcc : other).push_back(f);
    const StepDeviation dn = step_deviation(s, s1, nurcc), dx = step_deviation(s, s1, other);
    EXPECT_LT(dn.position, 1e-13);
    EXPECT_LT(dn.derivative, 1e-11);
    EXPECT_LT(dx.position, 1e-13);
    EXPECT_LT(dx.derivative, 1e-11);
    std::printf("box 7 x 7, strip %d at %.2f: one forced step against the mesh as given: %zu non-uniform faces %.1e / %.1e, %zu "
                "others (exact %d, bicubic %d) %.1e / %.1e\n", strip, wide, nurcc.size(), dn.position, dn.derivative, other.size(),
                s.count(FaceMethod::exact), s.count(FaceMethod::bicubic), dx.position, dx.derivative);
  }
}

// Star points 3 edges apart with a strip of unequal intervals: two steps (3 -> 12 edges), then NonUniformStar.
TEST(GlobalNurccStep, CloseStarPointsWithUnequalIntervalsAreStepped) {
  const TMesh mesh = stepped_box(3, 1, 1.5);
  EXPECT_EQ(nurcc_steps_needed(mesh, TMeshSurface::kStarsApart), 2);
  const TMeshSurface s(mesh, 1);
  EXPECT_EQ(s.global_steps(), 2);
  EXPECT_EQ(s.non_uniform_stars(), 0);  // after the steps the strip is beyond the star points' three rings
  const test::Continuity c = test::continuity(s.mesh(), [&](int f, double u, double v, double* o) { s.eval(f, u, v, o); });
  EXPECT_EQ(c.edges, 16 * 108);
  EXPECT_LT(c.gap, 1e-12);
  EXPECT_LT(c.normal_angle, 1e-9);
  EXPECT_LT(c.c1, 0.5 + 1e-9);  // C1 in the knots: across the strip's sides the derivatives differ by the ratio 1.5
  // Three steps: the same surface.
  const TMeshSurface s3(mesh, 1, 3);
  double gap = 0;
  for (int f = 0; f < static_cast<int>(mesh.faces.size()); ++f)
    for (const auto& [u, v] : stepped_samples()) {
      double x[9], y[9];
      s.eval_source(f, u, v, x);
      s3.eval_source(f, u, v, y);
      gap = std::max(gap, std::hypot(x[0] - y[0], x[1] - y[1], x[2] - y[2]));
    }
  EXPECT_LT(gap, 1e-13);
  const TSplineTriangulation t = tessellate(s, 1e-3);
  EXPECT_EQ(test::closed_euler_characteristic(t), 2);
  std::printf("box 3 x 3, strip at 1.5: 2 steps, %d faces (non-uniform %d, bicubic %d, exact %d); continuity gap %.1e, "
              "normals %.1e, C1 %.1e; 3 steps against 2: %.1e\n", s.num_faces(), s.count(FaceMethod::non_uniform),
              s.count(FaceMethod::bicubic), s.count(FaceMethod::exact), c.gap, c.normal_angle, c.c1, gap);
}

TEST(GlobalNurccStep, OpenMeshesAreRefused) {
  const test::QuadMesh q = test::fan_mesh(5, 4, [](double, double) { return 0.0; });
  const TMesh mesh = io::parse_tsm(test::tsm_text(q), "fan.tsm").mesh;
  try {
    nurcc_step(mesh);
    ADD_FAILURE() << "stepped an open mesh";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    EXPECT_NE(msg.find("global non-uniform Catmull-Clark step: edge"), std::string::npos) << msg;
    EXPECT_NE(msg.find("is on the boundary (closed meshes only)"), std::string::npos) << msg;
  }
}

}  // namespace
}  // namespace trivar
