// The exact-boundary integrals on single trimmed faces with holes, against closed forms: trimmed_volume of a
// one-face boundary without mesh is int (x S_u x S_v)_x over the trimmed domain, trimmed_integral the same
// with any F. The faces are written here by hand (the textbook NURBS of circles and surfaces of revolution,
// Piegl & Tiller 7.3 and 8.5; Bezier graphs), the holes bounded by iso-parameter lines at angles the quarter
// arcs reproduce exactly (knots at multiples of 90 degrees, span midpoints at 45 degrees by symmetry), drawn
// once as straight segments and once as rational quadratics (the same segments at a varying speed).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "trivar/model/trimmed_boundary.hpp"
#include "trivar/model/trimmed_integral.hpp"

namespace trivar {
namespace {

constexpr double kPi = std::numbers::pi;
const double kHalfRoot2 = std::sqrt(0.5);

// A surface of revolution about z: the unit circle's nine control points (four quarter arcs, u in [0, 4],
// u = k at 90k degrees) times a planar profile (rho, z, weight) with its knots.
TensorSpline<2> revolved_surface(const KnotVector& profile_knots, const std::vector<std::array<double, 3>>& profile) {
  const double cx[9] = {1, 1, 0, -1, -1, -1, 0, 1, 1}, cy[9] = {0, 1, 1, 1, 0, -1, -1, -1, 0};
  std::vector<double> coefs;
  for (const auto& [rho, z, wp] : profile)
    for (int i = 0; i < 9; ++i) {
      const double w = (i % 2 ? kHalfRoot2 : 1.0) * wp;
      coefs.insert(coefs.end(), {w * rho * cx[i], w * rho * cy[i], w * z, w});
    }
  return TensorSpline<2>({KnotVector(2, {0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4}), profile_knots}, 3, true, std::move(coefs));
}

// The segment from a to b in the parameter plane: degree 1, or a rational quadratic with its middle control
// point on the segment (the same points, traversed at a varying speed).
TensorSpline<1> segment_curve(std::array<double, 2> a, std::array<double, 2> b, bool rational) {
  if (!rational) return TensorSpline<1>({KnotVector(1, {0, 0, 1, 1})}, 2, false, {a[0], a[1], b[0], b[1]});
  const double w = 0.4, m0 = 0.3 * a[0] + 0.7 * b[0], m1 = 0.3 * a[1] + 0.7 * b[1];
  return TensorSpline<1>({KnotVector(2, {0, 0, 0, 1, 1, 1})}, 2, true, {a[0], a[1], 1, w * m0, w * m1, w, b[0], b[1], 1});
}

// The rectangle [u0, u1] x [v0, v1] as a loop: counter-clockwise (an outer loop) or clockwise (a hole).
TrimLoop rectangle_loop(double u0, double u1, double v0, double v1, bool hole, bool rational) {
  std::vector<std::array<double, 2>> c = {{u0, v0}, {u1, v0}, {u1, v1}, {u0, v1}};
  if (hole) std::reverse(c.begin(), c.end());
  TrimLoop loop;
  for (std::size_t k = 0; k < 4; ++k) loop.curves.push_back({segment_curve(c[k], c[(k + 1) % 4], rational)});
  return loop;
}

// One face: its domain as the outer loop, and the holes.
TrimmedBoundary one_face(TensorSpline<2> s, const std::vector<std::array<double, 4>>& holes, bool rational_trims) {
  TrimmedFace f;
  const Box<2> d = s.domain();
  f.surface = std::move(s);
  f.loops.push_back(rectangle_loop(d.lo[0], d.hi[0], d.lo[1], d.hi[1], false, rational_trims));
  for (const auto& h : holes) f.loops.push_back(rectangle_loop(h[0], h[1], h[2], h[3], true, rational_trims));
  TrimmedBoundary b;
  b.faces.push_back(std::move(f));
  return b;
}

// Antiderivatives of cos^2, cos^3 and cos^4.
double int_cos2(double t) { return t / 2 + std::sin(2 * t) / 4; }
double int_cos3(double t) { return std::sin(t) - std::pow(std::sin(t), 3) / 3; }
double int_cos4(double t) { return 3 * t / 8 + std::sin(2 * t) / 4 + std::sin(4 * t) / 32; }

// Sphere of radius R: u the longitude, v in [0, 2] the latitude from -90 to 90 degrees (outward normal).
TensorSpline<2> sphere_surface(double R) {
  return revolved_surface(KnotVector(2, {0, 0, 0, 1, 1, 2, 2, 2}),
                          {{0, -R, 1}, {R, -R, kHalfRoot2}, {R, 0, 1}, {R, R, kHalfRoot2}, {0, R, 1}});
}

TEST(TrimmedIntegral, SphereWithHolesMatchesClosedForms) {
  const double R = 1.7;
  // Holes: longitude 45..180 degrees by latitude -45..45, and 225..270 by 0..45 (each across knot lines).
  const std::vector<std::array<double, 4>> holes = {{0.5, 2, 0.5, 1.5}, {2.5, 3, 1, 1.5}};
  const double deg = kPi / 180;
  const std::vector<std::array<double, 4>> angles = {{45 * deg, 180 * deg, -45 * deg, 45 * deg}, {225 * deg, 270 * deg, 0, 45 * deg}};
  // x n_x dA = R^3 cos^2(theta) cos^3(phi) dtheta dphi; (x^2 / 2) n_x dA = R^4 / 2 cos^3(theta) cos^4(phi).
  double volume = 4 * kPi / 3 * R * R * R, moment = 0;
  for (const auto& a : angles) {
    volume -= R * R * R * (int_cos2(a[1]) - int_cos2(a[0])) * (int_cos3(a[3]) - int_cos3(a[2]));
    moment -= std::pow(R, 4) / 2 * (int_cos3(a[1]) - int_cos3(a[0])) * (int_cos4(a[3]) - int_cos4(a[2]));
  }
  for (bool rational_trims : {false, true}) {
    const TrimmedBoundary b = one_face(sphere_surface(R), holes, rational_trims);
    EXPECT_NEAR(trimmed_volume(b), volume, 1e-11 * volume) << rational_trims;
    EXPECT_NEAR(trimmed_integral(b, [](const std::array<double, 3>& x) { return x[0] * x[0] / 2; }), moment,
                1e-11 * std::abs(moment)) << rational_trims;
  }
  // The whole sphere, no hole.
  EXPECT_NEAR(trimmed_volume(one_face(sphere_surface(R), {}, false)), 4 * kPi / 3 * R * R * R, 1e-12 * R * R * R);
}

TEST(TrimmedIntegral, TorusWithHolesMatchesClosedForms) {
  const double Rc = 3, r = 1.2;
  // The tube's circle centred (Rc, 0) in the (rho, z) plane, v in [0, 4]: phi = 90 v degrees from the outer equator.
  const TensorSpline<2> torus = revolved_surface(
      KnotVector(2, {0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4}),
      {{Rc + r, 0, 1}, {Rc + r, r, kHalfRoot2}, {Rc, r, 1}, {Rc - r, r, kHalfRoot2}, {Rc - r, 0, 1},
       {Rc - r, -r, kHalfRoot2}, {Rc, -r, 1}, {Rc + r, -r, kHalfRoot2}, {Rc + r, 0, 1}});
  // x n_x dA = r cos^2(theta) cos(phi) (Rc + r cos(phi))^2 dtheta dphi.
  const auto along_phi = [&](double p) { return Rc * Rc * std::sin(p) + 2 * Rc * r * int_cos2(p) + r * r * int_cos3(p); };
  const double deg = kPi / 180;
  double volume = 2 * kPi * kPi * Rc * r * r;
  const std::vector<std::array<double, 4>> holes = {{0.5, 1.5, 0.5, 2.5}, {2.5, 3.5, 3, 3.5}};
  for (const auto& h : holes)
    volume -= r * (int_cos2(90 * h[1] * deg) - int_cos2(90 * h[0] * deg)) * (along_phi(90 * h[3] * deg) - along_phi(90 * h[2] * deg));
  for (bool rational_trims : {false, true})
    EXPECT_NEAR(trimmed_volume(one_face(torus, holes, rational_trims)), volume, 1e-11 * volume) << rational_trims;
}

TEST(TrimmedIntegral, CylinderWithHolesMatchesClosedForm) {
  // Radius R, z in [0, h]: rational around, linear along the axis (the polynomial inner direction).
  const double R = 2.5, h = 4;
  const TensorSpline<2> cylinder =
      revolved_surface(KnotVector(1, {0, 0, 1, 1}), {{R, 0, 1}, {R, h, 1}});
  const std::vector<std::array<double, 4>> holes = {{0.5, 2, 0.25, 0.75}, {3, 3.5, 0.1, 0.9}};
  const double deg = kPi / 180;
  double volume = kPi * R * R * h;
  for (const auto& k : holes) volume -= R * R * (int_cos2(90 * k[1] * deg) - int_cos2(90 * k[0] * deg)) * (k[3] - k[2]) * h;
  for (bool rational_trims : {false, true})
    EXPECT_NEAR(trimmed_volume(one_face(cylinder, holes, rational_trims)), volume, 1e-11 * volume) << rational_trims;
}

// The Bezier graph S(u, v) = (u, v, u^3 v) of bidegree (p, q): x n_x = -3 u^3 v, (x^2 / 2) n_x = -3/2 u^4 v over
// the unit square minus a hole. Degrees 3 and 4 along the inner direction (u: the directions tie on one span).
TEST(TrimmedIntegral, PolynomialGraphWithHoleMatchesClosedForm) {
  const std::array<double, 4> hole = {0.2, 0.7, 0.3, 0.9};
  const auto box = [&](double pu, double pv) {  // int u^pu v^pv over the square minus the hole
    return (1 - (std::pow(hole[1], pu + 1) - std::pow(hole[0], pu + 1)) * (std::pow(hole[3], pv + 1) - std::pow(hole[2], pv + 1))) /
           ((pu + 1) * (pv + 1));
  };
  for (const auto& [p, q] : {std::pair{3, 4}, std::pair{4, 3}, std::pair{3, 3}}) {
    // u^3 = sum_i C(i, 3) / C(p, 3) B_i^p(u); u and v by their Greville abscissae.
    std::vector<double> coefs;
    for (int j = 0; j <= q; ++j)
      for (int i = 0; i <= p; ++i) {
        const double c3 = i < 3 ? 0.0 : (i == 3 ? 1.0 : 4.0) / (p == 3 ? 1.0 : 4.0);
        coefs.insert(coefs.end(), {static_cast<double>(i) / p, static_cast<double>(j) / q, c3 * j / q});
      }
    std::vector<double> ku(static_cast<std::size_t>(p + 1), 0.0), kv(static_cast<std::size_t>(q + 1), 0.0);
    ku.resize(static_cast<std::size_t>(2 * p + 2), 1.0);
    kv.resize(static_cast<std::size_t>(2 * q + 2), 1.0);
    const TensorSpline<2> s({KnotVector(p, ku), KnotVector(q, kv)}, 3, false, coefs);
    for (bool rational_trims : {false, true}) {
      const TrimmedBoundary b = one_face(s, {hole}, rational_trims);
      EXPECT_NEAR(trimmed_volume(b), -3 * box(3, 1), 1e-13) << p << q << rational_trims;
      EXPECT_NEAR(trimmed_integral(b, [](const std::array<double, 3>& x) { return x[0] * x[0] / 2; }), -1.5 * box(4, 1), 1e-13)
          << p << q << rational_trims;
    }
  }
}

}  // namespace
}  // namespace trivar
