#include "trivar/spline/compatibility.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "support/spline_fixtures.hpp"
#include "trivar/core/error.hpp"
#include "trivar/spline/reparametrization.hpp"

using namespace trivar;

namespace {

// Inputs of different degrees, knots, rationality and clamping; input 2 is moved to another domain in every
// direction. Outputs must share knots, be rational, and reproduce the inputs (input 2 through the affine map).
template <int D>
void check_compatible() {
  Ints<D> p1, p2, p3, e1, e2, e3;
  for (int k = 0; k < D; ++k) {
    p1[k] = 1 + k % 2;
    p2[k] = 3 - k % 3;
    p3[k] = 2;
    e1[k] = 2 + k;
    e2[k] = 3;
    e3[k] = 1 + k;
  }
  auto moved = test::random_spline<D>(p3, e3, 3, false, 30 + D);
  std::vector<double> shift(D), scale(D);
  for (int k = 0; k < D; ++k) {
    shift[k] = -0.5 + k;
    scale[k] = 1.5 + 0.25 * k;
    const double a = moved.knots(k).start(), b = moved.knots(k).end();
    moved = reparametrize(moved, k, shift[k] + scale[k] * a, shift[k] + scale[k] * b);
  }
  const std::vector<TensorSpline<D>> in{test::random_spline<D>(p1, e1, 3, false, 10 + D),
                                        test::random_spline<D>(p2, e2, 3, true, 20 + D, false), moved};
  const auto out = make_compatible(in);
  ASSERT_EQ(out.size(), in.size());
  for (std::size_t i = 0; i < out.size(); ++i) {
    EXPECT_TRUE(out[i].is_rational());
    for (int k = 0; k < D; ++k) {
      EXPECT_EQ(out[i].knots(k), out[0].knots(k)) << "spline " << i << " direction " << k;
      EXPECT_EQ(out[i].degree(k), std::max({p1[k], p2[k], p3[k]}));
    }
  }
  for (int i = 0; i < 2; ++i) {
    const auto params = test::random_params(in[i], 200, 5 + i);
    EXPECT_LT(test::max_deviation(in[i], out[i], params), 1e-12) << "spline " << i;
    for (const auto& u : params) {
      const auto ref = test::reference_eval(out[i], u);
      const auto x = test::reference_eval(in[i], u);
      for (int d = 0; d < 3; ++d) ASSERT_NEAR(ref[d], x[d], 1e-12);
    }
  }
  std::vector<double> x(3), y(3);
  for (const auto& u : test::random_params(in[2], 200, 9)) {
    Param<D> t;
    for (int k = 0; k < D; ++k) t[k] = (u[k] - shift[k]) / scale[k];
    in[2].eval(u, x.data());
    out[2].eval(t, y.data());
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(x[d], y[d], 1e-12);
  }
}

}  // namespace

TEST(MakeCompatible, CurvesShareKnotsAndKeepGeometry) { check_compatible<1>(); }
TEST(MakeCompatible, SurfacesShareKnotsAndKeepGeometry) { check_compatible<2>(); }
TEST(MakeCompatible, VolumesShareKnotsAndKeepGeometry) { check_compatible<3>(); }

TEST(MakeCompatible, PolynomialInputsStayPolynomialAndUnchangedWhenAlreadyCompatible) {
  const auto a = test::random_spline<2>({2, 3}, {3, 2}, 2, false, 1);
  const auto b = test::random_spline<2>({2, 3}, {3, 2}, 2, false, 1);
  const auto out = make_compatible<2>({a, b});
  EXPECT_FALSE(out[0].is_rational());
  EXPECT_EQ(out[0].knots(0), a.knots(0));
  EXPECT_EQ(out[0].knots(1), a.knots(1));
  EXPECT_TRUE(make_compatible<2>({}).empty());
}

TEST(MakeCompatible, DifferentDimensionsThrow) {
  const auto a = test::random_spline<1>({2}, {3}, 2, false, 1);
  const auto b = test::random_spline<1>({2}, {3}, 3, false, 2);
  EXPECT_THROW(make_compatible<1>({a, b}), Error);
}
