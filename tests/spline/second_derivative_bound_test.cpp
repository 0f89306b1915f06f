#include "trivar/spline/second_derivative_bound.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace trivar {
namespace {

// A patch of degrees (p, q) with homogeneous coefficients (w x, w y, w z, w) from points and weights.
BezierElement<2> rational_patch(int p, int q, const std::vector<std::array<double, 3>>& points, const std::vector<double>& weights) {
  BezierElement<2> z;
  z.domain = Box<2>{{0, 0}, {1, 1}};
  z.degrees = {p, q};
  z.dim = 3;
  z.rational = true;
  for (std::size_t k = 0; k < points.size(); ++k) {
    for (double c : points[k]) z.coefs.push_back(weights[k] * c);
    z.coefs.push_back(weights[k]);
  }
  return z;
}

// x(u, v) of the patch by its definition, sum w P B / sum w B with B from the binomial formula.
std::array<double, 3> patch_point(const BezierElement<2>& z, double u, double v) {
  const int p = z.degrees[0], q = z.degrees[1];
  const auto bern = [](int n, int i, double t) {
    double c = 1;
    for (int k = 1; k <= i; ++k) c = c * (n - i + k) / k;
    return c * std::pow(t, i) * std::pow(1 - t, n - i);
  };
  double h[4] = {0, 0, 0, 0};
  for (int j = 0; j <= q; ++j)
    for (int i = 0; i <= p; ++i)
      for (int d = 0; d < 4; ++d) h[d] += bern(p, i, u) * bern(q, j, v) * z.coefs[static_cast<std::size_t>(4 * (i + (p + 1) * j) + d)];
  return {h[0] / h[3], h[1] / h[3], h[2] / h[3]};
}

// The largest second differences (step 1e-4) over a 41 x 41 grid: the sup of |x_uu|, |x_uv|, |x_vv| to about 1e-6.
SecondDerivativeBound sampled_second_derivatives(const BezierElement<2>& z) {
  const double h = 1e-4;
  SecondDerivativeBound s;
  const auto norm = [](const std::array<double, 3>& a) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); };
  for (int j = 0; j <= 40; ++j)
    for (int i = 0; i <= 40; ++i) {
      const double u = h + (1 - 2 * h) * i / 40, v = h + (1 - 2 * h) * j / 40;
      const auto c = patch_point(z, u, v);
      const auto e = patch_point(z, u + h, v), w = patch_point(z, u - h, v);
      const auto n = patch_point(z, u, v + h), so = patch_point(z, u, v - h);
      const auto ne = patch_point(z, u + h, v + h), nw = patch_point(z, u - h, v + h);
      const auto se = patch_point(z, u + h, v - h), sw = patch_point(z, u - h, v - h);
      std::array<double, 3> uu, vv, uv;
      for (int d = 0; d < 3; ++d) {
        uu[static_cast<std::size_t>(d)] = (e[d] - 2 * c[d] + w[d]) / (h * h);
        vv[static_cast<std::size_t>(d)] = (n[d] - 2 * c[d] + so[d]) / (h * h);
        uv[static_cast<std::size_t>(d)] = (ne[d] - nw[d] - se[d] + sw[d]) / (4 * h * h);
      }
      s.uu = std::max(s.uu, norm(uu));
      s.uv = std::max(s.uv, norm(uv));
      s.vv = std::max(s.vv, norm(vv));
    }
  return s;
}

TEST(SecondDerivativeBound, QuadraticPatchGivesItsConstantSecondDerivatives) {
  // x = (u, v, a u^2 + b u v + c v^2): Bernstein coefficients of u are (0, 1/2, 1), of u^2 (0, 0, 1).
  const double a = 1.5, b = -0.7, c = 0.25;
  std::vector<std::array<double, 3>> points;
  for (int j = 0; j <= 2; ++j)
    for (int i = 0; i <= 2; ++i) points.push_back({i / 2.0, j / 2.0, a * (i == 2) + b * (i / 2.0) * (j / 2.0) + c * (j == 2)});
  for (double w : {1.0, 2.0}) {  // equal weights: the same polynomial
    const SecondDerivativeBound s = second_derivative_bound(rational_patch(2, 2, points, std::vector<double>(9, w)));
    EXPECT_NEAR(s.uu, 2 * a, 1e-12) << w;
    EXPECT_NEAR(s.uv, std::abs(b), 1e-12) << w;
    EXPECT_NEAR(s.vv, 2 * c, 1e-12) << w;
  }
  BezierElement<2> plain;  // not rational
  plain.domain = Box<2>{{0, 0}, {1, 1}};
  plain.degrees = {2, 2};
  plain.dim = 3;
  for (const auto& x : points) plain.coefs.insert(plain.coefs.end(), x.begin(), x.end());
  const SecondDerivativeBound s = second_derivative_bound(plain);
  EXPECT_NEAR(s.uu, 2 * a, 1e-12);
  EXPECT_NEAR(s.uv, std::abs(b), 1e-12);
  EXPECT_NEAR(s.vv, 2 * c, 1e-12);
}

TEST(SecondDerivativeBound, QuarterCylinderIsBoundedTightlyAndStraightAlongItsAxis) {
  // The rational quadratic quarter circle of radius 1 (weights 1, 1/sqrt 2, 1), extruded by 2 along z.
  std::vector<std::array<double, 3>> points;
  std::vector<double> weights;
  for (double zc : {0.0, 2.0}) {
    points.insert(points.end(), {{1, 0, zc}, {1, 1, zc}, {0, 1, zc}});
    weights.insert(weights.end(), {1, std::sqrt(0.5), 1});
  }
  const BezierElement<2> z = rational_patch(2, 1, points, weights);
  const SecondDerivativeBound s = second_derivative_bound(z), ref = sampled_second_derivatives(z);
  EXPECT_GE(s.uu, ref.uu * (1 - 1e-5));
  EXPECT_LE(s.uu, 1.5 * ref.uu);  // 1.39: the Bernstein coefficients of W^3 and the numerator
  // x_uv = x_vv = 0: the numerators vanish identically.
  EXPECT_LT(s.uv, 1e-12);
  EXPECT_LT(s.vv, 1e-12);
  EXPECT_LT(ref.uv + ref.vv, 1e-5);
}

TEST(SecondDerivativeBound, BoundsRandomRationalBicubicsEverywhere) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coord(-1, 1), weight(0.5, 2);
  for (int trial = 0; trial < 4; ++trial) {
    std::vector<std::array<double, 3>> points;
    std::vector<double> weights;
    for (int j = 0; j <= 3; ++j)
      for (int i = 0; i <= 3; ++i) {
        points.push_back({i / 3.0 + 0.2 * coord(rng), j / 3.0 + 0.2 * coord(rng), 0.5 * coord(rng)});
        weights.push_back(weight(rng));
      }
    const BezierElement<2> z = rational_patch(3, 3, points, weights);
    const SecondDerivativeBound s = second_derivative_bound(z), ref = sampled_second_derivatives(z);
    EXPECT_GE(s.uu, ref.uu * (1 - 1e-5)) << trial;
    EXPECT_GE(s.uv, ref.uv * (1 - 1e-5)) << trial;
    EXPECT_GE(s.vv, ref.vv * (1 - 1e-5)) << trial;
  }
}

TEST(SecondDerivativeBound, NonPositiveWeightIsUnbounded) {
  std::vector<std::array<double, 3>> points;
  for (int j = 0; j <= 1; ++j)
    for (int i = 0; i <= 1; ++i) points.push_back({double(i), double(j), 0});
  const SecondDerivativeBound s = second_derivative_bound(rational_patch(1, 1, points, {1, -0.5, 1, 1}));
  EXPECT_TRUE(std::isinf(s.uu) && std::isinf(s.uv) && std::isinf(s.vv));
}

}  // namespace
}  // namespace trivar
