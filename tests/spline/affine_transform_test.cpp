#include "trivar/spline/affine_transform.hpp"

#include <gtest/gtest.h>

#include "support/spline_fixtures.hpp"
#include "trivar/core/error.hpp"

using namespace trivar;

namespace {

template <int D>
double deviation(const TensorSpline<D>& s, const TensorSpline<D>& r, const Eigen::MatrixXd& A,
                 const Eigen::VectorXd& b, unsigned seed) {
  double m = 0;
  std::vector<double> y(r.dim());
  for (const auto& u : test::random_params(s, 300, seed)) {
    const auto ref = test::reference_eval(s, u);
    const Eigen::VectorXd expected = A * Eigen::Map<const Eigen::VectorXd>(ref.data(), s.dim()) + b;
    r.eval(u, y.data());
    for (int d = 0; d < r.dim(); ++d) m = std::max(m, std::abs(expected[d] - y[d]));
  }
  return m;
}

}  // namespace

TEST(AffineTransform, RationalVolumeMapsExactly) {
  for (bool rational : {false, true}) {
    const auto s = test::random_spline<3>({2, 3, 2}, {3, 2, 3}, 3, rational, 501);
    Eigen::MatrixXd A(3, 3);
    A << 0.3, -1.2, 2.0, 0.7, 0.1, -0.4, 1.5, 0.9, 0.2;
    Eigen::VectorXd b(3);
    b << 4.0, -2.0, 0.5;
    const auto r = transform(s, A, b);
    EXPECT_EQ(r.is_rational(), rational);
    EXPECT_LE(deviation(s, r, A, b, 502), 1e-12);
    // Weights are untouched.
    for (int i = 0; i < s.num_coefs(); ++i) EXPECT_EQ(r.weight(i), s.weight(i));
  }
}

TEST(AffineTransform, RotationKeepsCircleRadius) {
  // Rational quadratic quarter circle of radius 2 centred at the origin, rotated and translated.
  const double h = std::sqrt(0.5);
  const auto c = SplineCurve::from_cartesian({KnotVector(2, {0, 0, 0, 1, 1, 1})}, 2,
                                             std::vector<double>{2, 0, 2, 2, 0, 2}, std::vector<double>{1, h, 1});
  const double a = 0.7;
  Eigen::MatrixXd R(2, 2);
  R << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  Eigen::VectorXd t(2);
  t << 3.0, -1.0;
  const auto r = transform(c, R, t);
  double p[2];
  for (int i = 0; i <= 50; ++i) {
    r.eval({i / 50.0}, p);
    EXPECT_NEAR(std::hypot(p[0] - 3.0, p[1] + 1.0), 2.0, 1e-14);
  }
}

TEST(AffineTransform, EmbeddingIntoHigherDimension) {
  const auto s = test::random_spline<2>({2, 3}, {2, 2}, 2, true, 503);
  Eigen::MatrixXd A(3, 2);
  A << 1, 0, 0, 1, 0.5, -0.25;
  Eigen::VectorXd b(3);
  b << 0, 0, 1;
  const auto r = transform(s, A, b);
  EXPECT_EQ(r.dim(), 3);
  EXPECT_LE(deviation(s, r, A, b, 504), 1e-12);
}

TEST(AffineTransform, RejectsSizeMismatch) {
  const auto s = test::random_spline<2>({2, 2}, {2, 2}, 3, false, 505);
  EXPECT_THROW(transform(s, Eigen::MatrixXd::Identity(2, 2), Eigen::VectorXd::Zero(2)), Error);
  EXPECT_THROW(transform(s, Eigen::MatrixXd::Identity(3, 3), Eigen::VectorXd::Zero(2)), Error);
}
