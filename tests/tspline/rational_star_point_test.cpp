// T-meshes with star points and control points of weights other than 1 (rational Catmull-Clark): the faces
// near a star point against the rational T-spline of a chart around them (an independent evaluation: Bezier
// extraction of sum w P B / sum w B), continuity across every edge and at the star point, and the Bezier patches
// of such a mesh (rational patches: exact pieces against the surface, corners within the tolerance).
#include <gtest/gtest.h>

#include <cstdio>

#include "chart_comparison.hpp"
#include "face_continuity.hpp"
#include "star_mesh_tsm.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/tsm_format.hpp"
#include "trivar/tspline/t_mesh_patches.hpp"
#include "trivar/tspline/t_mesh_surface.hpp"
#include "trivar/tspline/t_spline_surface.hpp"

namespace trivar {
namespace {

double rational_fan_height(double x, double y) { return 0.05 * x * x - 0.03 * x * y + 0.2 * std::sin(0.4 * y); }

// The valence-N fan of m x m faces per sector with every point's weight a smooth function of its position, from
// 0.6 to 1.8 (the end-condition blocks' points take their vertex's weight, as a Rhino export does).
TMesh weighted_fan(int valence, int m) {
  io::TsmModel model = io::parse_tsm(test::tsm_text(test::fan_mesh(valence, m, rational_fan_height)), "weighted_fan.tsm");
  for (RationalPoint& p : model.mesh.points) p.w = 1.2 + 0.6 * std::sin(0.7 * p.xyz[0] + 0.45 * p.xyz[1] + 0.3);
  return model.mesh;
}

// Every Catmull-Clark face without a star corner whose two face rings hold no star point is the rational
// T-spline of the chart of those rings (its 16 blending functions and their knots lie inside), to rounding.
TEST(RationalStarPoints, CatmullClarkFacesAreTheRationalTSpline) {
  for (int valence : {3, 5}) {
    const TMesh mesh = weighted_fan(valence, 8);
    const TMeshSurface s(mesh, 1);
    EXPECT_EQ(s.count(FaceMethod::star), valence);
    EXPECT_EQ(s.count(FaceMethod::bicubic), valence * 25 - valence);  // as with weights 1
    const test::ChartComparison cmp = test::compare_with_charts(mesh, s, FaceMethod::bicubic);
    const int compared = cmp.compared;
    const double worst = cmp.position, worst_derivative = cmp.derivative;
    EXPECT_GT(compared, valence * 10) << valence;
    EXPECT_LT(worst, 1e-12) << valence;
    EXPECT_LT(worst_derivative, 1e-11) << valence;
    std::printf("rational valence-%d fan: %d Catmull-Clark faces against the chart's rational T-spline: positions %.1e, "
                "first derivatives %.1e\n", valence, compared, worst, worst_derivative);
  }
}

// One smooth surface: C0 (to rounding) and C1 across every edge (the rational limit is the quotient of C1
// functions), and one tangent plane at the star point from all its faces; weights that differ from 1 do change it.
TEST(RationalStarPoints, SmoothAcrossEveryEdgeAndAtTheStarPoint) {
  for (int valence : {3, 5}) {
    const TMesh mesh = weighted_fan(valence, 8);
    const TMeshSurface s(mesh, 1);
    const test::Continuity c = test::continuity(mesh, [&](int f, double u, double v, double* o) { s.eval(f, u, v, o); });
    EXPECT_LT(c.gap, 1e-12) << valence;
    EXPECT_LT(c.normal_angle, 1e-10) << valence;
    EXPECT_LT(c.c1, 1e-9) << valence;
    // At the star point: the limit normal from each star face, and the normals just off it.
    std::vector<std::array<double, 3>> normals;
    double off = 0;
    for (int f = 0; f < s.num_faces(); ++f) {
      if (s.method(f) != FaceMethod::star) continue;
      const auto at = corner_frame(s.patch_corner(f)).origin;
      double o[9];
      s.eval(f, at[0], at[1], o);
      normals.push_back(test::unit_normal(o));
      const double u = at[0] == 0 ? 1e-9 : 1 - 1e-9, v = at[1] == 0 ? 1e-9 : 1 - 1e-9;
      double q[9];
      s.eval(f, u, v, q);
      const auto n = test::unit_normal(q);
      off = std::max(off, std::hypot(n[0] - normals.back()[0], n[1] - normals.back()[1], n[2] - normals.back()[2]));
    }
    ASSERT_EQ(static_cast<int>(normals.size()), valence);
    double spread = 0;
    for (const auto& n : normals)
      spread = std::max(spread, std::hypot(n[0] - normals[0][0], n[1] - normals[0][1], n[2] - normals[0][2]));
    EXPECT_LT(spread, 1e-12) << valence;
    EXPECT_LT(off, 1e-3) << valence;  // the normal converges to the limit normal (like lambda^j, j ~ 30 levels)
    // The weights matter: the same mesh with weights 1 is another surface.
    TMesh unit = mesh;
    for (RationalPoint& p : unit.points) p.w = 1;
    const TMeshSurface u(unit, 1);
    double moved = 0;
    for (int f = 0; f < s.num_faces(); ++f)
      if (s.method(f) == FaceMethod::star) {
        double a[9], b[9];
        s.eval(f, 0.5, 0.5, a);
        u.eval(f, 0.5, 0.5, b);
        moved = std::max(moved, std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]));
      }
    EXPECT_GT(moved, 1e-3) << valence;
    std::printf("rational valence-%d fan: across %d edges: gap %.1e, normal jump (sine) %.1e, C1 defect %.1e; at the "
                "star point: normals of its faces within %.1e\n", valence, c.edges, c.gap, c.normal_angle, c.c1, spread);
  }
}

// The Bezier patches of a rational mesh: rational where the weights are not 1, exact pieces on the surface,
// corner patches within the tolerance, C0 across every edge and G1 at the star point.
TEST(RationalStarPoints, BezierPatchesAreRationalAndMeetTheTolerance) {
  const TMesh mesh = weighted_fan(5, 8);
  const TMeshSurface s(mesh, 1);
  const TMeshPatches p = t_mesh_patches(s);
  EXPECT_LE(p.deviation, p.tolerance);
  double exact = 0, corner = 0;
  int rational = 0;
  for (const FacePatch& q : p.patches) {
    rational += q.surface.is_rational();
    for (double a : {0.0, 0.31, 0.5, 1.0})
      for (double b : {0.0, 0.67, 1.0}) {
        const double u = q.piece.lo[0] + a * q.piece.extent(0), v = q.piece.lo[1] + b * q.piece.extent(1);
        double x[9], y[3];
        s.eval(q.face, u, v, x);
        q.surface.eval({u, v}, y);
        double& worst = q.exact ? exact : corner;
        worst = std::max(worst, std::hypot(x[0] - y[0], x[1] - y[1], x[2] - y[2]));
      }
  }
  EXPECT_EQ(rational, static_cast<int>(p.patches.size()));
  EXPECT_LT(exact, 1e-12);
  EXPECT_LE(corner, 2 * p.tolerance);
  // G1 at the star point: each corner patch's normal there is the limit normal.
  double star_normal = 0;
  for (const FacePatch& q : p.patches) {
    if (q.exact) continue;
    const auto at = corner_frame(s.patch_corner(q.face)).origin;
    double x[9], y[9];
    q.surface.eval_derivs({at[0], at[1]}, 1, x);
    s.eval(q.face, at[0], at[1], y);
    const auto a = test::unit_normal(x), b = test::unit_normal(y);
    star_normal = std::max(star_normal, std::hypot(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]));
  }
  EXPECT_LT(star_normal, 1e-12);
  std::printf("rational valence-5 fan as Bezier patches: %zu rational patches, %d levels, exact pieces off the surface by "
              "%.1e, corner patches by %.2e (tolerance %.2e), normal at the star point %.1e\n",
              p.patches.size(), p.levels, exact, corner, p.tolerance, star_normal);
}

}  // namespace
}  // namespace trivar
