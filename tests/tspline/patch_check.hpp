#pragma once
// A T-mesh surface's Bezier patches (t_mesh_patches) measured against the surface's own evaluation: each patch
// at 5 x 5 points of its piece, the pieces' areas per face, and the gaps where two pieces of a face or the
// patches of two faces meet.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "face_continuity.hpp"
#include "trivar/tspline/t_mesh_patches.hpp"

namespace trivar::test {

struct PatchCheck {
  double exact = 0;        // largest |patch - surface| over the patches marked exact
  double constructed = 0;  // over the corner patches
  double area = 0;         // largest |sum of the pieces' areas - 1| over the faces
  double inner_gap = 0;    // largest gap where the sides of two exact pieces of a face meet
  double corner_gap = 0;   // where a corner patch's side meets another piece of its face
  double edge_gap = 0;     // across the face edges
};

inline PatchCheck check_patches(const TMeshSurface& s, const TMeshPatches& p) {
  PatchCheck r;
  std::vector<std::vector<const FacePatch*>> of(static_cast<std::size_t>(s.num_faces()));
  for (const FacePatch& q : p.patches) of[static_cast<std::size_t>(q.face)].push_back(&q);
  const auto at = [](const FacePatch& q, double a, double b) {
    return std::array<double, 2>{q.piece.lo[0] + a * q.piece.extent(0), q.piece.lo[1] + b * q.piece.extent(1)};
  };
  const auto gap = [](const double* x, const double* y) { return std::hypot(x[0] - y[0], x[1] - y[1], x[2] - y[2]); };
  for (int f = 0; f < s.num_faces(); ++f) {
    const auto& pieces = of[static_cast<std::size_t>(f)];
    if (s.method(f) == FaceMethod::none) continue;
    double area = 0;
    for (const FacePatch* q : pieces) {
      area += q->piece.extent(0) * q->piece.extent(1);
      for (int j = 0; j <= 4; ++j)
        for (int i = 0; i <= 4; ++i) {
          const auto uv = at(*q, i / 4.0, j / 4.0);
          double x[9], y[3];
          s.eval(f, uv[0], uv[1], x);
          q->surface.eval({uv[0], uv[1]}, y);
          double& worst = q->exact ? r.exact : r.constructed;
          worst = std::max(worst, gap(x, y));
        }
      for (int side = 0; side < 4; ++side)
        for (double t : {0.0, 0.25, 0.5, 0.75, 1.0}) {
          const auto st = side_uv(side, t);
          const auto uv = at(*q, st[0], st[1]);
          double x[3];
          q->surface.eval({uv[0], uv[1]}, x);
          for (const FacePatch* o : pieces) {
            if (o == q || !o->piece.contains({uv[0], uv[1]}, 1e-15)) continue;
            double y[3];
            o->surface.eval({uv[0], uv[1]}, y);
            double& worst = q->exact && o->exact ? r.inner_gap : r.corner_gap;
            worst = std::max(worst, gap(x, y));
          }
        }
    }
    r.area = std::max(r.area, std::abs(area - 1));
  }
  const auto patched = [&](int f, double u, double v, double* out) {
    std::fill(out, out + 9, 1e300);  // a point no piece holds shows as a gap
    for (const FacePatch* q : of[static_cast<std::size_t>(f)])
      if (q->piece.contains({u, v}, 1e-15)) return q->surface.eval_derivs({u, v}, 1, out);
  };
  r.edge_gap = continuity(s.mesh(), patched).gap;
  return r;
}

// check_patches of p, and that it holds: exact patches the surface, the pieces tiling each face and meeting C0, to
// rounding; the corner patches within twice the tolerance. `what` names the case in failures.
inline PatchCheck expect_patches_hold(const TMeshSurface& s, const TMeshPatches& p, const std::string& what = {}) {
  const PatchCheck c = check_patches(s, p);
  EXPECT_LT(c.exact, 1e-12) << what;
  EXPECT_LE(c.constructed, 2 * p.tolerance) << what;
  EXPECT_LT(c.area, 1e-12) << what;
  EXPECT_LT(c.inner_gap, 1e-12) << what;
  EXPECT_LT(c.edge_gap, 1e-12) << what;
  EXPECT_LE(c.corner_gap, 2 * p.tolerance) << what;
  return c;
}

}  // namespace trivar::test
