#include "trivar/model/metamorphosis.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "support/spline_fixtures.hpp"
#include "trivar/core/error.hpp"
#include "trivar/model/ruled.hpp"

using namespace trivar;

namespace {

// Smoothstep blends written out: b_0 = t, b_1 = 3t^2 - 2t^3, b_2 = 10t^3 - 15t^4 + 6t^5.
double blend(int k, double t) {
  if (k == 0) return t;
  if (k == 1) return t * t * (3 - 2 * t);
  return t * t * t * (10 + t * (-15 + 6 * t));
}

const SplineSurface s0 = test::random_spline<2>({2, 1}, {3, 2}, 3, false, 11);
const SplineSurface s1 = test::random_spline<2>({1, 3}, {2, 4}, 3, false, 12);

}  // namespace

TEST(Metamorphosis, ReproducesTheInputsAndTheBlend) {
  for (int k = 0; k <= 2; ++k) {
    const auto v = metamorphosis(s0, s1, k);
    EXPECT_EQ(v.degree(2), 2 * k + 1);
    double faces = 0, inside = 0;
    for (const auto& u : test::random_params(v, 500, 13 + k)) {
      double a[3], b[3], x[3], y[3], z[3];
      s0.eval({u[0], u[1]}, a);
      s1.eval({u[0], u[1]}, b);
      v.eval({u[0], u[1], 0.0}, x);
      v.eval({u[0], u[1], 1.0}, y);
      v.eval(u, z);
      for (int d = 0; d < 3; ++d) {
        faces = std::max({faces, std::abs(x[d] - a[d]), std::abs(y[d] - b[d])});
        inside = std::max(inside, std::abs(z[d] - (a[d] + blend(k, u[2]) * (b[d] - a[d]))));
      }
    }
    EXPECT_LE(faces, 1e-12) << k;
    EXPECT_LE(inside, 1e-12) << k;
  }
}

TEST(Metamorphosis, LinearIsRuled) {
  const auto v = metamorphosis(s0, s1);
  const auto r = ruled<3>(s0, s1);
  ASSERT_EQ(v.coefs().size(), r.coefs().size());
  for (std::size_t i = 0; i < v.coefs().size(); ++i) ASSERT_EQ(v.coefs()[i], r.coefs()[i]);
}

TEST(Metamorphosis, EasesInAndOut) {
  const auto v = metamorphosis(s0, s1, 2);
  for (const auto& u : test::random_params(s0, 50, 17))
    for (const double t : {0.0, 1.0}) {
      double d[4 * 3];  // value, d/du, d/dv, d/dt
      v.eval_derivs({u[0], u[1], t}, 1, d);
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(d[9 + c], 0, 1e-12);
    }
}

TEST(Metamorphosis, InvalidInputThrows) {
  EXPECT_THROW(metamorphosis(s0, s1, -1), Error);
  EXPECT_THROW(metamorphosis(s0, test::random_spline<2>({1, 1}, {1, 1}, 2, false, 3), 1), Error);
}
