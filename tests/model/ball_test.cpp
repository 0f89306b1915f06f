#include "trivar/model/ball.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "support/spline_fixtures.hpp"
#include "trivar/core/error.hpp"
#include "trivar/spline/iso_extraction.hpp"
#include "trivar/spline/jacobian.hpp"
#include "trivar/spline/measure.hpp"

using namespace trivar;

TEST(Ball, CubeSpherePatchIsExactlySpherical) {
  const auto s = cube_sphere_patch(1.0);
  double worst = 0;
  for (const auto& u : test::random_params(s, 5000, 1)) {
    double x[3];
    s.eval(u, x);
    worst = std::max(worst, std::abs(std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) - 1));
    ASSERT_GT(x[2], 0.0);
  }
  EXPECT_LE(worst, 1e-12);
  // Corners are the cube's vertices (+-1, +-1, 1) / sqrt 3, u along x, v along y.
  const double c = 1 / std::sqrt(3.0);
  for (const auto& [u, v] : {std::pair{0.0, 0.0}, std::pair{1.0, 0.0}, std::pair{0.0, 1.0}, std::pair{1.0, 1.0}}) {
    double x[3];
    s.eval({u, v}, x);
    EXPECT_NEAR(x[0], u ? c : -c, 1e-15);
    EXPECT_NEAR(x[1], v ? c : -c, 1e-15);
    EXPECT_NEAR(x[2], c, 1e-15);
  }
  // Six such patches tile the sphere: one patch has a sixth of its area.
  EXPECT_NEAR(measure(s, 16), 4 * std::numbers::pi / 6, 1e-10);
}

TEST(Ball, VolumeIsFourThirdsPiR3) {
  const double R = 1.7;
  const auto cells = make_ball({.radius = R, .center = Eigen::Vector3d(0.3, -0.2, 1.0)});
  ASSERT_EQ(cells.size(), 7u);
  double v = 0;
  for (const auto& c : cells) v += signed_measure(c, 16);
  EXPECT_NEAR(v / (4.0 / 3.0 * std::numbers::pi * R * R * R), 1.0, 1e-9);
}

TEST(Ball, EveryCellCertifiedValidOverCoreRange) {
  for (const double core : {0.2, 0.6, 0.8})
    for (const auto& c : make_ball({.radius = 0.9, .core = core})) {
      const auto rep = check_jacobian(c);
      EXPECT_TRUE(rep.valid) << "core " << core << " min lower bound " << rep.min_lower_bound;
    }
}

TEST(Ball, BoundaryAtExactRadius) {
  const double R = 1.7;
  const Eigen::Vector3d center(0.3, -0.2, 1.0);
  const auto cells = make_ball({.radius = R, .center = center});
  double worst = 0;
  for (int c = 1; c <= 6; ++c) {
    const auto face = iso_extract(cells[c], 2, 1.0);
    for (const auto& u : test::random_params(face, 1000, 40 + c)) {
      Eigen::Vector3d x;
      face.eval(u, x.data());
      worst = std::max(worst, std::abs((x - center).norm() - R));
    }
  }
  EXPECT_LE(worst, 1e-12 * R);
}

TEST(Ball, InvalidDimensionsThrow) {
  EXPECT_THROW(make_ball({.radius = -1}), Error);
  EXPECT_THROW(make_ball({.radius = 0}), Error);
  EXPECT_THROW(make_ball({.radius = 1, .core = 1}), Error);
  EXPECT_THROW(make_ball({.radius = 1, .center = Eigen::Vector3d(0, std::nan(""), 0)}), Error);
  EXPECT_THROW(cube_sphere_patch(-2), Error);
}
