#include "trivar/spline/closest_point.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "support/spline_fixtures.hpp"
#include "trivar/core/error.hpp"
#include "trivar/spline/degree_elevation.hpp"
#include "trivar/spline/knot_insertion.hpp"

using namespace trivar;

namespace {

const double kH = std::sqrt(0.5);
const double kPi = std::numbers::pi;

// Octant of the sphere of radius R centred at c (x, y, z >= 0 relative to c): a quarter meridian (pole to
// equator) revolved by a quarter turn about z, both exact rational quadratic arcs. Degenerate at the pole.
SplineSurface sphere_octant(double R, const double* c) {
  const double merid[3][2] = {{1, 0}, {1, 1}, {0, 1}};  // (rho, z) from the equator to the pole
  const double turn[3][2] = {{1, 0}, {1, 1}, {0, 1}};   // (x, y) quarter circle
  const double w[3] = {1, kH, 1};
  std::vector<double> pts, wts;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      pts.push_back(c[0] + R * merid[j][0] * turn[i][0]);
      pts.push_back(c[1] + R * merid[j][0] * turn[i][1]);
      pts.push_back(c[2] + R * merid[j][1]);
      wts.push_back(w[i] * w[j]);
    }
  const KnotVector q(2, {0, 0, 0, 1, 1, 1});
  return SplineSurface::from_cartesian({q, q}, 3, pts, wts);
}

// Quarter cylinder x^2 + y^2 = R^2, x, y >= 0, z in [0, H]; refined so it has several elements.
SplineSurface cylinder_quarter(double R, double H) {
  std::vector<double> pts, wts;
  const double arc[3][2] = {{1, 0}, {1, 1}, {0, 1}};
  const double w[3] = {1, kH, 1};
  for (int k = 0; k < 2; ++k)
    for (int i = 0; i < 3; ++i) {
      pts.insert(pts.end(), {R * arc[i][0], R * arc[i][1], H * k});
      wts.push_back(w[i]);
    }
  const auto s = SplineSurface::from_cartesian({KnotVector(2, {0, 0, 0, 1, 1, 1}), KnotVector(1, {0, 0, 1, 1})}, 3,
                                               pts, wts);
  return refine_uniform(elevate_degree(s, Ints<2>{0, 2}), Ints<2>{3, 2});
}

}  // namespace

TEST(ClosestPoint, SphereOctantInteriorAndBoundary) {
  const double c[3] = {0.5, -1.0, 2.0}, R = 1.5;
  const auto s = sphere_octant(R, c);
  std::mt19937 rng(701);
  std::uniform_real_distribution<double> U(-1.0, 1.0), T(0.2, 3.0);
  for (int i = 0; i < 200; ++i) {
    double d[3];
    for (double& v : d) v = U(rng);
    const double n = std::hypot(d[0], d[1], d[2]);
    if (n < 0.1) continue;
    for (double& v : d) v /= n;
    const double t = T(rng) * R;
    const double x[3] = {c[0] + t * d[0], c[1] + t * d[1], c[2] + t * d[2]};
    // The closest point of the sphere is c + R d; restricted to the octant, negative components of d drop out
    // (the maximiser of d . e over unit e >= 0 is the normalised positive part of d).
    double e[3], ne = 0;
    for (int k = 0; k < 3; ++k) {
      e[k] = std::max(d[k], 0.0);
      ne += e[k] * e[k];
    }
    if (ne < 1e-4) continue;  // the nearest point is then a vertex of the octant; skip the near-tie
    ne = std::sqrt(ne);
    double expected = 0;
    for (int k = 0; k < 3; ++k) {
      const double p = c[k] + R * e[k] / ne;
      expected += (x[k] - p) * (x[k] - p);
    }
    expected = std::sqrt(expected);
    const auto r = closest_point(s, x);
    EXPECT_TRUE(r.converged) << "direction " << d[0] << " " << d[1] << " " << d[2] << ", t " << t;
    EXPECT_NEAR(r.distance, expected, 1e-10) << i;
    const auto y = test::reference_eval(s, r.param);
    EXPECT_NEAR(std::hypot(y[0] - r.point[0], y[1] - r.point[1], y[2] - r.point[2]), 0.0, 1e-12);
  }
}

TEST(ClosestPoint, SphereCentreTerminatesWithTheRadius) {
  const double c[3] = {0, 0, 0};
  const auto s = sphere_octant(2.0, c);
  const auto r = closest_point(s, c);
  EXPECT_NEAR(r.distance, 2.0, 1e-12);
}

TEST(ClosestPoint, CylinderPatchWithEdges) {
  const double R = 0.8, H = 2.0;
  const auto s = cylinder_quarter(R, H);
  std::mt19937 rng(702);
  std::uniform_real_distribution<double> Rr(0.05, 3.0), Th(0.0, kPi / 2), Z(-1.0, 3.0);
  for (int i = 0; i < 200; ++i) {
    const double r = Rr(rng), t = Th(rng), z = Z(rng);
    const double x[3] = {r * std::cos(t), r * std::sin(t), z};
    const double dz = z < 0 ? -z : (z > H ? z - H : 0.0);
    const double expected = std::hypot(r - R, dz);
    const auto res = closest_point(s, x);
    EXPECT_TRUE(res.converged);
    EXPECT_NEAR(res.distance, expected, 1e-10) << r << " " << t << " " << z;
    EXPECT_NEAR(std::hypot(res.point[0], res.point[1]), R, 1e-12);
    EXPECT_NEAR(res.point[2], std::clamp(z, 0.0, H), 1e-9);
  }
}

TEST(ClosestPoint, PlanePatchIsOrthogonalProjection) {
  // A bicubic patch in the plane through o spanned by orthonormal e1, e2: control points on a perturbed grid,
  // so the parametrisation is not affine but the surface is planar.
  const double o[3] = {1.0, 2.0, -0.5};
  const double e1[3] = {2.0 / 3, 2.0 / 3, 1.0 / 3}, e2[3] = {-2.0 / 3, 1.0 / 3, 2.0 / 3};
  const double nrm[3] = {1.0 / 3, -2.0 / 3, 2.0 / 3};  // e1 x e2
  std::mt19937 rng(703);
  std::array<KnotVector, 2> kv{test::random_knots(3, 3, rng), test::random_knots(3, 2, rng)};
  std::uniform_real_distribution<double> P(-0.03, 0.03);
  std::vector<double> pts;
  for (double b : kv[1].greville())
    for (double a : kv[0].greville()) {
      const double s1 = 2 * a + P(rng), s2 = 1.5 * b + P(rng);
      for (int d = 0; d < 3; ++d) pts.push_back(o[d] + s1 * e1[d] + s2 * e2[d]);
    }
  const auto s = SplineSurface::from_cartesian(kv, 3, pts);
  std::uniform_real_distribution<double> Hh(-2.0, 2.0);
  for (const auto& u : test::random_params(s, 200, 704)) {
    const auto p = test::reference_eval(s, u);
    const double h = Hh(rng);
    const double x[3] = {p[0] + h * nrm[0], p[1] + h * nrm[1], p[2] + h * nrm[2]};
    const auto r = closest_point(s, x);
    EXPECT_TRUE(r.converged);
    EXPECT_NEAR(r.distance, std::abs(h), 1e-10);
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(r.point[d], p[d], 1e-9);
  }
}

TEST(ClosestPoint, CircleArcCurve) {
  const double R = 1.7;
  const auto c = SplineCurve::from_cartesian({KnotVector(2, {0, 0, 0, 1, 1, 1})}, 2,
                                             std::vector<double>{R, 0, R, R, 0, R}, std::vector<double>{1, kH, 1});
  std::mt19937 rng(705);
  std::uniform_real_distribution<double> Rr(0.1, 4.0), Th(-kPi / 4, 3 * kPi / 4);
  for (int i = 0; i < 200; ++i) {
    const double r = Rr(rng), t = Th(rng);
    const double x[2] = {r * std::cos(t), r * std::sin(t)};
    // Inside the arc's angular range: |r - R|; outside: distance to the nearer end point.
    double expected;
    if (t >= 0 && t <= kPi / 2) expected = std::abs(r - R);
    else expected = std::min(std::hypot(x[0] - R, x[1]), std::hypot(x[0], x[1] - R));
    const auto res = closest_point(c, x);
    EXPECT_NEAR(res.distance, expected, 1e-10) << r << " " << t;
  }
}

TEST(ClosestPoint, RejectsBadTolerance) {
  const auto s = test::random_spline<2>({2, 2}, {2, 2}, 3, false, 706);
  const double x[3] = {0, 0, 0};
  EXPECT_THROW(closest_point(s, x, 0.0), Error);
}
