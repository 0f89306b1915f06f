#include "trivar/model/block.hpp"

#include <gtest/gtest.h>

#include "support/spline_fixtures.hpp"
#include "trivar/core/error.hpp"
#include "trivar/spline/derivative_index.hpp"

using namespace trivar;

TEST(Block, VolumeIsTheScaledIdentity) {
  const Param<3> size{2.0, 0.5, 3.0};
  const auto b = make_block<3>({2, 3, 1}, {3, 2, 4}, size);
  EXPECT_EQ(b.dim(), 3);
  EXPECT_FALSE(b.is_rational());
  EXPECT_EQ(b.count(0), 5);
  EXPECT_EQ(b.count(1), 5);
  EXPECT_EQ(b.count(2), 5);
  std::vector<double> d(static_cast<std::size_t>(derivative_count(3, 1)) * 3);
  for (const auto& u : test::random_params(b, 300, 1)) {
    b.eval_derivs(u, 1, d.data());
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(d[k], size[k] * u[k], 1e-14);
      // Jacobian rows: d x / d u_j = size_j e_j.
      for (int j = 0; j < 3; ++j) EXPECT_NEAR(d[3 * (1 + j) + k], j == k ? size[k] : 0.0, 1e-13);
    }
  }
}

TEST(Block, SurfaceAndCurveLieInModelSpace) {
  const auto s = make_block<2>({2, 2}, {2, 3}, {4.0, 1.0});
  EXPECT_EQ(s.dim(), 3);
  for (const auto& u : test::random_params(s, 100, 2)) {
    double x[3];
    s.eval(u, x);
    EXPECT_NEAR(x[0], 4.0 * u[0], 1e-14);
    EXPECT_NEAR(x[1], u[1], 1e-14);
    EXPECT_EQ(x[2], 0.0);
  }
  const auto c = make_block<1>({3}, {5}, {2.0});
  double x[3];
  c.eval({0.3}, x);
  EXPECT_NEAR(x[0], 0.6, 1e-14);
  EXPECT_EQ(x[1], 0.0);
  EXPECT_EQ(x[2], 0.0);
}

TEST(Block, RectangleProfileInTheXzPlane) {
  // u along the axis, v radial: the normal S_u x S_v = (0, 0, 1.5) x (2, 0, 0) points to +y.
  const auto p = make_rectangle_profile({-1.0, 0.5}, {1.0, 3.0}, {2, 1}, {2, 2});
  std::vector<double> d(static_cast<std::size_t>(derivative_count(2, 1)) * 3);
  for (const auto& u : test::random_params(p, 100, 3)) {
    p.eval_derivs(u, 1, d.data());
    EXPECT_NEAR(d[0], 1.0 + 2.0 * u[1], 1e-14);
    EXPECT_EQ(d[1], 0.0);
    EXPECT_NEAR(d[2], -1.0 + 1.5 * u[0], 1e-14);
    EXPECT_NEAR(d[3 + 2] * d[6 + 0] - d[3 + 0] * d[6 + 2], 3.0, 1e-13);
  }
}

TEST(Block, RejectsBadInput) {
  EXPECT_THROW(make_block<3>({0, 1, 1}, {1, 1, 1}, {1, 1, 1}), Error);
  EXPECT_THROW(make_block<3>({1, 1, 1}, {1, 0, 1}, {1, 1, 1}), Error);
  EXPECT_THROW(make_block<3>({1, 1, 1}, {1, 1, 1}, {1, -1, 1}), Error);
  EXPECT_THROW(make_block<2>({1, 1}, {1, 1}, {1, std::nan("")}), Error);
  EXPECT_THROW(make_rectangle_profile({0, 1}, {2, 1}), Error);
  EXPECT_THROW(make_rectangle_profile({1, 1}, {1, 2}), Error);
}
