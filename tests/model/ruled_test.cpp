#include "trivar/model/ruled.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>

#include "support/spline_fixtures.hpp"
#include "trivar/core/error.hpp"
#include "trivar/spline/affine_transform.hpp"
#include "trivar/spline/degree_elevation.hpp"
#include "trivar/spline/knot_insertion.hpp"
#include "trivar/spline/measure.hpp"

using namespace trivar;

namespace {

// ruled(a, b)(u, w) against (1 - w) a(u) + w b(u) evaluated directly from the inputs.
template <int D>
void check_blend(const TensorSpline<D - 1>& a, const TensorSpline<D - 1>& b) {
  const auto r = ruled<D>(a, b);
  ASSERT_EQ(r.knots(D - 1), KnotVector(1, {0, 0, 1, 1}));
  std::vector<double> x(a.dim()), y(a.dim()), z(a.dim());
  for (const auto& u : test::random_params(r, 300, 4)) {
    Param<D - 1> s;
    for (int k = 0; k + 1 < D; ++k) s[k] = u[k];
    a.eval(s, x.data());
    b.eval(s, y.data());
    r.eval(u, z.data());
    const double w = u[D - 1];
    for (int d = 0; d < a.dim(); ++d) ASSERT_NEAR(z[d], (1 - w) * x[d] + w * y[d], 1e-12);
  }
}

}  // namespace

TEST(Ruled, IncompatibleCurvesGiveExactBlend) {
  check_blend<2>(test::random_spline<1>({2}, {3}, 3, false, 1), test::random_spline<1>({4}, {2}, 3, false, 2));
}

TEST(Ruled, IncompatibleSurfacesGiveExactBlend) {
  check_blend<3>(test::random_spline<2>({2, 1}, {3, 2}, 3, false, 3),
                 test::random_spline<2>({1, 3}, {2, 4}, 3, false, 4, false));
}

TEST(Ruled, ParallelPlanarPatchesGiveAreaTimesDistance) {
  // A curved planar patch in z = 0 (interior control points moved within the plane), and its translate by an
  // oblique vector, represented with other degrees and knots: Cavalieri gives volume = area * height.
  auto a = test::random_spline<2>({2, 3}, {2, 2}, 3, false, 7);
  const auto n = a.counts();
  for (int j = 0; j < n[1]; ++j)
    for (int i = 0; i < n[0]; ++i) {
      double* c = a.coefs().data() + 3 * a.linear_index({i, j});
      c[0] = 3.0 * i / (n[0] - 1) + 0.2 * c[0];
      c[1] = 2.0 * j / (n[1] - 1) + 0.2 * c[1];
      c[2] = 0;
    }
  const double height = 0.8;
  auto b = transform(a, Eigen::MatrixXd::Identity(3, 3), Eigen::Vector3d(0.3, -0.4, height));
  b = elevate_degree(b, {1, 0});
  const std::vector<double> extra{0.37, 1.21};
  b = insert_knots(b, 1, extra);
  const double area = measure(a, 8);
  const auto vol = ruled<3>(a, b);
  EXPECT_NEAR(std::abs(signed_measure(vol, 8)), area * height, 1e-11);
  EXPECT_NEAR(measure(vol, 8), area * height, 1e-11);
}

TEST(Ruled, DifferentDimensionsThrow) {
  EXPECT_THROW(ruled<2>(test::random_spline<1>({2}, {3}, 3, false, 1), test::random_spline<1>({2}, {3}, 2, false, 2)),
               Error);
}
