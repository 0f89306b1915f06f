#include "trivar/model/sweep.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "support/spline_fixtures.hpp"
#include "trivar/core/error.hpp"
#include "trivar/model/circle_arc.hpp"
#include "trivar/model/extrude.hpp"
#include "trivar/spline/affine_transform.hpp"
#include "trivar/spline/jacobian.hpp"

using namespace trivar;

namespace {

// A curved rational patch in the xz-plane about (2, 0, 0) with S_u x S_v along +y: the outer cell of a
// disk, placed by (x, y) -> (2 + x, 0, -y).
SplineSurface arc_profile() {
  Eigen::Matrix3d place = Eigen::Matrix3d::Zero();
  place(0, 0) = 1;
  place(2, 1) = -1;
  return transform(disk_cells(0.5, 0.6)[1], place, Eigen::Vector3d(2, 0, 0));
}

// Quarter circle of radius 2 about the z-axis from (2, 0, 0), tangent +y at the start.
SplineCurve quarter_circle() {
  return circle_arc(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), 2.0, 0,
                    0.5 * std::numbers::pi);
}

// Max |V - exact sweep| on a dense grid. Along a planar curve the rotation-minimising frame keeps the
// plane's normal, so the exact sweep is the profile turned about the z-axis by the polar angle of path(w).
double measured_error(const SplineVolume& v, const SplineSurface& profile, const SplineCurve& path) {
  double worst = 0;
  for (int k = 0; k <= 400; ++k) {
    const double w = k / 400.0;
    double c[3];
    path.eval({w}, c);
    const double phi = std::atan2(c[1], c[0]);
    const Eigen::Matrix3d R = Eigen::AngleAxisd(phi, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    for (int i = 0; i <= 8; ++i)
      for (int j = 0; j <= 8; ++j) {
        Eigen::Vector3d s, x;
        profile.eval({i / 8.0, j / 8.0}, s.data());
        v.eval({i / 8.0, j / 8.0, w}, x.data());
        worst = std::max(worst, (x - R * s).norm());
      }
  }
  return worst;
}

}  // namespace

TEST(Sweep, StraightLineEqualsExtrusion) {
  const auto profile = test::random_spline<2>({2, 3}, {2, 2}, 3, true, 5);
  // A straight path with non-uniform speed (degree 2): the frame is constant and the path in the fit space.
  const std::vector<double> pts{0, 0, 0, 0.1, 0.2, 0.5, 0.4, 0.8, 2.0};
  const auto path = SplineCurve::from_cartesian({KnotVector(2, {0, 0, 0, 1, 1, 1})}, 3, pts);
  const auto res = sweep(profile, path, {.sections = 3});
  const auto ext = extrude_along<3>(profile, path);
  double worst = 0;
  for (const auto& u : test::random_params(ext, 2000, 6)) {
    Eigen::Vector3d a, b;
    res.volume.eval(u, a.data());
    ext.eval(u, b.data());
    worst = std::max(worst, (a - b).norm());
  }
  EXPECT_LE(worst, 1e-12);
  EXPECT_LE(res.max_error, 1e-12);
}

TEST(Sweep, CircleArcConvergesAtFourthOrderAndReportsItsError) {
  const auto profile = arc_profile();
  const auto path = quarter_circle();
  // Measured errors: 5.2e-3, 8.6e-4, 3.9e-5, 2.3e-6 for 2, 4, 8, 16 sections (pre-asymptotic at first).
  double previous = 0;
  for (const int sections : {4, 8, 16, 32}) {
    const auto res = sweep(profile, path, {.sections = sections, .samples = 40});
    const double measured = measured_error(res.volume, profile, path);
    EXPECT_LE(measured, 1.02 * res.max_error) << sections;
    EXPECT_GE(measured, 0.5 * res.max_error) << sections;
    if (previous > 0) {
      EXPECT_GT(previous / measured, 12.0) << sections;  // cubic fit: ratio 16 per halving
    }
    previous = measured;
  }
  EXPECT_LT(previous, 2e-7);
}

TEST(Sweep, ProfileNormalAlongTangentGivesValidVolume) {
  const auto res = sweep(arc_profile(), quarter_circle(), {.sections = 4});
  EXPECT_TRUE(check_jacobian(res.volume).valid);
}

TEST(Sweep, FrameDoesNotTwistAboutTheTangent) {
  // A space curve: the frame vector r may only change along t (r' = -(k . r) t), never along s.
  const std::vector<double> pts{0, 0, 0, 1, 0, 0.5, 1, 1, -0.5, 0, 1.5, 1};
  const auto path = SplineCurve::from_cartesian({KnotVector(3, {0, 0, 0, 0, 1, 1, 1, 1})}, 3, pts);
  const double h = 1e-4;
  for (const double w : {0.2, 0.5, 0.8}) {
    const std::vector<double> at{w - h, w, w + h};
    const auto f = rotation_minimizing_frames(path, at, 1e-4);
    const Eigen::Vector3d dr = (f[2].col(1) - f[0].col(1)) / (2 * h);
    EXPECT_LT(std::abs(dr.dot(f[1].col(2))), 1e-6) << w;
    EXPECT_GT(std::abs(dr.dot(f[1].col(0))), 1e-2) << w;  // it does turn with the tangent
    EXPECT_NEAR((f[1].transpose() * f[1] - Eigen::Matrix3d::Identity()).norm(), 0, 1e-12);
  }
}

TEST(Sweep, InvalidInputThrows) {
  const auto path = quarter_circle();
  EXPECT_THROW(sweep(test::random_spline<2>({2, 2}, {1, 1}, 2, false, 1), path), Error);
  EXPECT_THROW(sweep(arc_profile(), path, {.sections = 0}), Error);
  const std::vector<double> still{1, 2, 3, 1, 2, 3};
  const auto point = SplineCurve::from_cartesian({KnotVector(1, {0, 0, 1, 1})}, 3, still);
  EXPECT_THROW(sweep(arc_profile(), point), Error);
}
