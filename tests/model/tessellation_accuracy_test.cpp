// The boundary meshes of the exact primitives against their analytic surfaces: the largest distance of any
// point of any triangle from the surface stays within the chordal tolerance, the triangle count follows the
// 1 / tolerance law of curved surfaces, flat faces stay coarse, triangles are well shaped and the mesh is a
// closed oriented surface of the right genus.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "trivar/core/error.hpp"
#include "trivar/model/ball.hpp"
#include "trivar/model/block.hpp"
#include "trivar/model/brep_from_surfaces.hpp"
#include "trivar/model/cylinder.hpp"
#include "trivar/model/model_tessellation.hpp"
#include "trivar/model/torus.hpp"
#include "trivar/spline/iso_extraction.hpp"
#include "support/model_fixtures.hpp"

using namespace trivar;

namespace {

using Vec = std::array<double, 3>;
using Vec2 = std::array<double, 2>;

double length(const Vec& a) { return std::hypot(a[0], a[1], a[2]); }
Vec sub(const Vec& a, const Vec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

std::array<Vec, 3> corners(const TriangleMesh& m, const std::array<int, 3>& t) {
  return {m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]};
}

// Closest point of triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5).
Vec closest_on_triangle(const Vec& p, const Vec& a, const Vec& b, const Vec& c) {
  const Vec ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  const auto at = [&](double v, double w) {
    return Vec{a[0] + v * ab[0] + w * ac[0], a[1] + v * ab[1] + w * ac[1], a[2] + v * ab[2] + w * ac[2]};
  };
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec bp = sub(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return at(d1 / (d1 - d3), 0);
  const Vec cp = sub(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return at(0, d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return at(1 - w, w);
  }
  const double denom = 1 / (va + vb + vc);
  return at(vb * denom, vc * denom);
}

// Largest distance of a point of the triangle from the sphere |x| = R. |x| is convex, so its maximum over
// the triangle is at a corner and its minimum at the point closest to the centre.
double sphere_deviation(const std::array<Vec, 3>& t, double R) {
  double d = 0;
  for (const Vec& x : t) d = std::max(d, std::abs(length(x) - R));
  return std::max(d, R - length(closest_on_triangle({0, 0, 0}, t[0], t[1], t[2])));
}

// Smallest distance from the origin to a triangle in the plane (zero inside it).
double distance_to_origin_2d(const std::array<Vec2, 3>& t) {
  const auto cross = [](const Vec2& a, const Vec2& b) { return a[0] * b[1] - a[1] * b[0]; };
  double s[3];
  for (int i = 0; i < 3; ++i) s[i] = cross(t[i], t[(i + 1) % 3]);
  if ((s[0] > 0 && s[1] > 0 && s[2] > 0) || (s[0] < 0 && s[1] < 0 && s[2] < 0)) return 0;
  double d = 1e300;
  for (int i = 0; i < 3; ++i) {
    const Vec2 &a = t[i], &b = t[(i + 1) % 3];
    const Vec2 e{b[0] - a[0], b[1] - a[1]};
    const double ee = e[0] * e[0] + e[1] * e[1];
    const double w = ee > 0 ? std::clamp(-(a[0] * e[0] + a[1] * e[1]) / ee, 0.0, 1.0) : 0.0;
    d = std::min(d, std::hypot(a[0] + w * e[0], a[1] + w * e[1]));
  }
  return d;
}

// Largest distance of a triangle of the cylinder r <= R, 0 <= z <= H from its boundary: a triangle with all
// corners on a cap lies in the cap's plane; any other has all corners on the side (checked) and its
// distance from the side is R minus its smallest distance from the axis.
double cylinder_deviation(const std::array<Vec, 3>& t, double R, double H, bool& on_cap) {
  on_cap = std::all_of(t.begin(), t.end(), [](const Vec& x) { return std::abs(x[2]) < 1e-12; }) ||
           std::all_of(t.begin(), t.end(), [&](const Vec& x) { return std::abs(x[2] - H) < 1e-12; });
  if (on_cap) {
    double r = 0;
    for (const Vec& x : t) r = std::max(r, std::hypot(x[0], x[1]));
    EXPECT_LE(r, R * (1 + 1e-12));
    return 0;
  }
  for (const Vec& x : t) EXPECT_NEAR(std::hypot(x[0], x[1]), R, 1e-12);
  return R - distance_to_origin_2d({Vec2{t[0][0], t[0][1]}, Vec2{t[1][0], t[1][1]}, Vec2{t[2][0], t[2][1]}});
}

// Largest distance of the triangle from the torus (tube of radius r about the circle of radius R in z = 0),
// by the exact distance sqrt((rho - R)^2 + z^2) - r at the corners, the edge midpoints and a barycentric
// grid of 12 steps per edge (91 points).
double torus_deviation(const std::array<Vec, 3>& t, double R, double r) {
  double d = 0;
  constexpr int n = 12;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; i + j <= n; ++j) {
      const double a = double(i) / n, b = double(j) / n, c = 1 - a - b;
      Vec x;
      for (int k = 0; k < 3; ++k) x[k] = a * t[0][k] + b * t[1][k] + c * t[2][k];
      d = std::max(d, std::abs(std::hypot(std::hypot(x[0], x[1]) - R, x[2]) - r));
    }
  return d;
}

double min_angle_degrees(const TriangleMesh& m) {
  double worst = 180;
  for (const auto& tri : m.triangles) {
    const auto t = corners(m, tri);
    for (int i = 0; i < 3; ++i) {
      const Vec e1 = sub(t[(i + 1) % 3], t[i]), e2 = sub(t[(i + 2) % 3], t[i]);
      worst = std::min(worst, std::acos(std::clamp(dot(e1, e2) / (length(e1) * length(e2)), -1.0, 1.0)) * 180 / std::numbers::pi);
    }
  }
  return worst;
}

// Cells are at most twice as long as wide in space and fanned from their centres, with at most one
// neighbour corner per side, in its middle half: in a 2 : 1 rectangle the smallest fan angle is then
// 45 - atan(1/2) = 18.4 degrees (corner at a quarter of the long side). The
// primitives' parametrisations are skewed (sides meet at 60 to 120 degrees at the sphere patches' corners),
// which lowers it; 10 degrees leaves room for that.
constexpr double kMinAngle = 10.0;

}  // namespace

TEST(TessellationAccuracy, BallStaysWithinTheToleranceOfTheSphere) {
  for (double R : {1.0, 2.0}) {
    const VModel ball = test::glued(make_ball({.radius = R}));
    for (double tol : {0.02, 0.01, 0.005, 0.002}) {
      const ModelTessellation t = tessellate_boundary(ball, {.chordal_tolerance = tol});
      double worst = 0;
      for (const auto& tri : t.mesh.triangles) worst = std::max(worst, sphere_deviation(corners(t.mesh, tri), R));
      EXPECT_LE(worst, tol) << "R " << R << " tol " << tol;
      // Not far finer than asked for either.
      EXPECT_GE(worst, 0.1 * tol) << "R " << R << " tol " << tol;
      EXPECT_TRUE(is_watertight(t.mesh));
      EXPECT_EQ(euler_characteristic(t.mesh), 2);
      EXPECT_GE(min_angle_degrees(t.mesh), kMinAngle) << "R " << R << " tol " << tol;
    }
  }
}

TEST(TessellationAccuracy, TriangleCountDoublesWhenTheToleranceHalves) {
  // On a sphere of radius R, triangles of diameter h deviate by about h^2 / (8 R) from it: the count,
  // area / h^2, grows like 1 / tolerance.
  const VModel ball = test::glued(make_ball({.radius = 1.0}));
  double previous = 0;
  for (double tol = 0.04; tol > 0.0007; tol /= 2) {
    const auto n = static_cast<double>(tessellate_boundary(ball, {.chordal_tolerance = tol}).mesh.triangles.size());
    if (previous > 0) {
      EXPECT_GE(n / previous, 1.5) << tol;
      EXPECT_LE(n / previous, 2.7) << tol;
    }
    previous = n;
  }
}

TEST(TessellationAccuracy, CylinderSideWithinToleranceAndCapsCoarse) {
  const double R = 1.0, H = 2.0;
  const VModel cyl = test::glued(make_cylinder({.radius = R, .height = H}));
  double previous_caps = 0, previous_side = 0;
  for (double tol : {0.004, 0.002, 0.001, 0.0005}) {
    const ModelTessellation t = tessellate_boundary(cyl, {.chordal_tolerance = tol});
    EXPECT_TRUE(is_watertight(t.mesh));
    EXPECT_EQ(euler_characteristic(t.mesh), 2);
    EXPECT_GE(min_angle_degrees(t.mesh), kMinAngle) << tol;
    double worst = 0, caps = 0, side = 0;
    for (const auto& tri : t.mesh.triangles) {
      bool on_cap = false;
      worst = std::max(worst, cylinder_deviation(corners(t.mesh, tri), R, H, on_cap));
      (on_cap ? caps : side) += 1;
    }
    EXPECT_LE(worst, tol) << tol;
    EXPECT_GE(worst, 0.1 * tol) << tol;
    // The flat caps only follow their rim, whose segment count grows like 1 / sqrt(tolerance); the side
    // grows like 1 / tolerance.
    if (previous_caps > 0) {
      EXPECT_LE(caps / previous_caps, 1.8) << tol;
      EXPECT_GE(side / previous_side, 1.5) << tol;
      EXPECT_LE(side / previous_side, 2.7) << tol;
    }
    EXPECT_LT(caps, side) << tol;
    previous_caps = caps;
    previous_side = side;
  }
}

TEST(TessellationAccuracy, TorusStaysWithinTheToleranceOfTheTube) {
  const double R = 2.0, r = 0.5;
  const VModel torus = test::glued(make_torus({.major_radius = R, .minor_radius = r}));
  for (double tol : {0.01, 0.003}) {
    const ModelTessellation t = tessellate_boundary(torus, {.chordal_tolerance = tol});
    EXPECT_TRUE(is_watertight(t.mesh));
    EXPECT_EQ(euler_characteristic(t.mesh), 0);
    EXPECT_GE(min_angle_degrees(t.mesh), kMinAngle) << tol;
    double worst = 0;
    for (const auto& tri : t.mesh.triangles) worst = std::max(worst, torus_deviation(corners(t.mesh, tri), R, r));
    EXPECT_LE(worst, tol) << tol;
  }
}

TEST(TessellationAccuracy, FlatFacesDoNotDependOnTheTolerance) {
  // A box whose faces are cut by knots and elongated 8 : 1: the triangles follow the knots and the shape,
  // never the tolerance.
  const TensorSpline<3> box = make_block<3>({2, 1, 1}, {3, 1, 2}, {8.0, 1.0, 2.0});
  const auto f = boundary_faces(box);
  const Brep brep = brep_from_surfaces({f.begin(), f.end()});
  std::size_t first = 0;
  for (double tol : {1e-1, 1e-3, 1e-5, 1e-7}) {
    const BrepTessellation t = tessellate(brep, {.chordal_tolerance = tol});
    EXPECT_TRUE(is_watertight(t.mesh));
    EXPECT_NEAR(enclosed_volume(t.mesh), 16.0, 1e-12);
    if (first == 0) first = t.mesh.triangles.size();
    EXPECT_EQ(t.mesh.triangles.size(), first) << tol;
  }
  EXPECT_LT(first, 1000u);
}

TEST(TessellationAccuracy, ToleranceBeyondMemoryIsRefusedByName) {
  const VModel ball = test::glued(make_ball({.radius = 1.0}));
  try {
    tessellate_boundary(ball, {.chordal_tolerance = 1e-9});
    FAIL() << "expected a refusal";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("chordal tolerance 1e-09"), std::string::npos) << what;
    EXPECT_NE(what.find("triangles"), std::string::npos) << what;
  }
}
