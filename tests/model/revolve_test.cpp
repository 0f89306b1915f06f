#include "trivar/model/revolve.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <Eigen/Geometry>

#include "support/spline_fixtures.hpp"
#include "trivar/core/error.hpp"
#include "trivar/model/block.hpp"
#include "trivar/spline/derivative_index.hpp"
#include "trivar/spline/measure.hpp"

using namespace trivar;

namespace {

using std::numbers::pi;

struct Axis {
  Eigen::Vector3d point, dir;
  double radius(const Eigen::Vector3d& x) const { return (x - point - height(x) * dir).norm(); }
  double height(const Eigen::Vector3d& x) const { return (x - point).dot(dir); }
  // Signed angle of x about the axis, measured from the radial direction of `from`.
  double angle(const Eigen::Vector3d& from, const Eigen::Vector3d& x) const {
    const Eigen::Vector3d a = from - point - height(from) * dir, b = x - point - height(x) * dir;
    return std::atan2(dir.dot(a.cross(b)), a.dot(b));
  }
};

}  // namespace

TEST(Revolve, RectangleProfileGivesExactRadiiAndHeights) {
  const double r0 = 0.7, r1 = 2.3, z0 = -0.4, z1 = 1.1;
  const Axis z_axis{{0, 0, 0}, {0, 0, 1}};
  for (double angle : {pi / 2, 2 * pi / 3, pi, 4.0, 2 * pi}) {
    const auto profile = make_rectangle_profile({z0, z1}, {r0, r1}, {1, 2}, {2, 3});
    const auto vol = revolve<3>(profile, z_axis.point, z_axis.dir, angle);
    ASSERT_TRUE(vol.is_rational());
    for (const auto& u : test::random_params(vol, 500, 11)) {
      Eigen::Vector3d x;
      vol.eval(u, x.data());
      EXPECT_NEAR(z_axis.radius(x), r0 + u[1] * (r1 - r0), 1e-12);
      EXPECT_NEAR(x.z(), z0 + u[0] * (z1 - z0), 1e-12);
    }
    // The sweep starts on the profile and ends at the requested angle; the angle grows with w.
    Eigen::Vector3d start, end;
    vol.eval({0.3, 0.6, 0.0}, start.data());
    vol.eval({0.3, 0.6, 1.0}, end.data());
    EXPECT_NEAR(start.y(), 0, 1e-15);
    const double expected_end = angle > pi ? angle - 2 * pi : angle;
    EXPECT_NEAR(z_axis.angle(start, end), expected_end, 1e-12);
    double previous = -1;
    for (int j = 0; j <= 50; ++j) {
      Eigen::Vector3d x;
      vol.eval({0.3, 0.6, j / 50.0}, x.data());
      const double a = std::atan2(x.y(), x.x());
      const double unwrapped = a < -1e-12 ? a + 2 * pi : a;
      if (j < 50 || angle < 2 * pi) {
        EXPECT_GT(unwrapped, previous);
      }
      previous = unwrapped;
    }
  }
}

TEST(Revolve, FullTurnHasNineControlPointsAndQuarterKnots) {
  const auto vol = revolve<3>(make_rectangle_profile({0, 1}, {1, 2}), {0, 0, 0}, {0, 0, 1}, 2 * pi);
  const KnotVector& kv = vol.knots(2);
  EXPECT_EQ(kv.degree(), 2);
  EXPECT_EQ(vol.count(2), 9);
  const std::vector<double> expected{0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1};
  EXPECT_EQ(kv.knots(), expected);
  // Weights along the angular direction: 1, cos 45, 1, ... for a bilinear (non-rational) profile.
  for (int j = 0; j < 9; ++j)
    EXPECT_NEAR(vol.weight(vol.linear_index({1, 1, j})), j % 2 ? std::sqrt(0.5) : 1.0, 1e-15);
  // Quarter turns are exact in floating point: control point (2, 0, 1) goes through the square corners
  // (2, 2, 1), (-2, 2, 1), ... and the axis points (0, 2, 1), (-2, 0, 1), ... and back to (2, 0, 1).
  const double expected_xy[9][2] = {{2, 0}, {2, 2}, {0, 2}, {-2, 2}, {-2, 0}, {-2, -2}, {0, -2}, {2, -2}, {2, 0}};
  for (int j = 0; j < 9; ++j) {
    double x[3];
    vol.control_point(vol.linear_index({1, 1, j}), x);
    EXPECT_EQ(x[0], expected_xy[j][0]) << j;
    EXPECT_EQ(x[1], expected_xy[j][1]) << j;
    EXPECT_EQ(x[2], 1.0) << j;
  }
}

TEST(Revolve, SegmentsPerStartedQuarterTurn) {
  const auto profile = make_rectangle_profile({0, 1}, {1, 2});
  const std::vector<std::pair<double, int>> cases{{0.3, 1}, {pi / 2, 1}, {pi / 2 + 1e-6, 2}, {pi, 2}, {1.5 * pi, 3}, {5.0, 4}};
  for (const auto& [angle, segments] : cases) {
    const auto vol = revolve<3>(profile, {0, 0, 0}, {0, 0, 1}, angle);
    EXPECT_EQ(vol.knots(2).num_elements(), segments) << angle;
    EXPECT_EQ(vol.count(2), 2 * segments + 1);
    EXPECT_NEAR(vol.weight(vol.linear_index({0, 0, 1})), std::cos(angle / segments / 2), 1e-15);
  }
}

TEST(Revolve, RationalProfileWeightsMultiply) {
  // A rational, non-planar profile about a tilted axis: every point keeps its distance to the axis and its
  // height along it, and the result's weights are profile weight times angular weight.
  const auto profile = test::random_spline<2>({2, 3}, {2, 2}, 3, true, 21);
  const Axis axis{{0.2, -0.1, 0.3}, Eigen::Vector3d(1, 2, -0.5).normalized()};
  const double angle = 2.5;
  const auto vol = revolve<3>(profile, axis.point, 3.0 * axis.dir, angle);
  EXPECT_NEAR(vol.weight(vol.linear_index({2, 1, 1})), profile.weight(profile.linear_index({2, 1})) * std::cos(angle / 4),
              1e-15);
  for (const auto& u : test::random_params(vol, 500, 22)) {
    Eigen::Vector3d x, p, start;
    vol.eval(u, x.data());
    profile.eval({u[0], u[1]}, p.data());
    vol.eval({u[0], u[1], 0.0}, start.data());
    EXPECT_NEAR(axis.radius(x), axis.radius(p), 1e-12);
    EXPECT_NEAR(axis.height(x), axis.height(p), 1e-12);
    EXPECT_NEAR((start - p).norm(), 0, 1e-12);
  }
  Eigen::Vector3d p, end;
  profile.eval({0.5, 1.0}, p.data());
  vol.eval({0.5, 1.0, 1.0}, end.data());
  EXPECT_NEAR(axis.angle(p, end), angle, 1e-12);
}

TEST(Revolve, VolumeOfRevolvedAnnulusByQuadrature) {
  const double r0 = 0.5, r1 = 1.75, z0 = 0.25, z1 = 2.0, h = z1 - z0;
  for (double angle : {pi / 2, 2.0, 2 * pi}) {
    const auto vol = revolve<3>(make_rectangle_profile({z0, z1}, {r0, r1}, {2, 1}, {1, 2}), {0, 0, 0}, {0, 0, 1}, angle);
    const double exact = pi * (r1 * r1 - r0 * r0) * h * angle / (2 * pi);
    EXPECT_NEAR(signed_measure(vol, 24), exact, 1e-10) << angle;  // signed: checks the orientation too
  }
}

TEST(Revolve, CurveToSurfaceGivesCylinderArea) {
  // A vertical segment at radius r swept by the angle a is a cylinder patch of area r * a * height.
  const double r = 1.5, height = 2.0, angle = 3.0;
  const SplineCurve line({KnotVector(1, {0, 0, 1, 1})}, 3, false, {r, 0, 0, r, 0, height});
  const auto surf = revolve<2>(line, {0, 0, 0}, {0, 0, 1}, angle);
  for (const auto& u : test::random_params(surf, 200, 31)) {
    Eigen::Vector3d x;
    surf.eval(u, x.data());
    EXPECT_NEAR(std::hypot(x.x(), x.y()), r, 1e-12);
  }
  EXPECT_NEAR(measure(surf, 24), r * angle * height, 1e-10);
}

TEST(Revolve, RejectsBadInput) {
  const auto profile = make_rectangle_profile({0, 1}, {1, 2});
  EXPECT_THROW(revolve<3>(profile, {0, 0, 0}, {0, 0, 0}, 1.0), Error);
  EXPECT_THROW(revolve<3>(profile, {0, 0, 0}, {0, 0, 1}, 0.0), Error);
  EXPECT_THROW(revolve<3>(profile, {0, 0, 0}, {0, 0, 1}, -1.0), Error);
  EXPECT_THROW(revolve<3>(profile, {0, 0, 0}, {0, 0, 1}, 2 * pi + 1e-9), Error);
  EXPECT_THROW(revolve<3>(profile, {0, 0, 0}, {0, 0, 1}, std::nan("")), Error);
  const auto planar = test::random_spline<2>({1, 1}, {1, 1}, 2, false, 41);
  EXPECT_THROW(revolve<3>(planar, {0, 0, 0}, {0, 0, 1}, 1.0), Error);
}
