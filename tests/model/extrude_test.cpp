#include "trivar/model/extrude.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "support/spline_fixtures.hpp"
#include "trivar/core/error.hpp"
#include "trivar/model/ruled.hpp"
#include "trivar/spline/measure.hpp"

using namespace trivar;

namespace {

// Exact rational quarter circle of radius r about the origin in z = 0, counter-clockwise from the x-axis.
SplineCurve quarter_arc(double r) {
  const double h = std::sqrt(0.5);
  const std::vector<double> pts{r, 0, 0, r, r, 0, 0, r, 0};
  const std::vector<double> w{1, h, 1};
  return SplineCurve::from_cartesian({KnotVector(2, {0, 0, 0, 1, 1, 1})}, 3, pts, w);
}

void extrude_sector(double r0, double r1, double height) {
  // u along the arc, v radial: the ruled sector between coaxial arcs is exact (equal weights).
  const auto sector = ruled<2>(quarter_arc(r0), quarter_arc(r1));
  const auto vol = extrude<3>(sector, Eigen::Vector3d(0, 0, height));
  for (const auto& u : test::random_params(vol, 300, 2)) {
    Eigen::Vector3d x;
    vol.eval(u, x.data());
    EXPECT_NEAR(std::hypot(x.x(), x.y()), r0 + u[1] * (r1 - r0), 1e-12);
    EXPECT_NEAR(x.z(), u[2] * height, 1e-12);
  }
  const double area = std::numbers::pi / 4 * (r1 * r1 - r0 * r0);
  // (S_u x S_v) points along -z (tangent x outward radial), the extrusion along +z: left-handed.
  EXPECT_NEAR(signed_measure(vol, 12), -area * height, 1e-10) << "r0 = " << r0;
}

}  // namespace

TEST(Extrude, QuarterCircleArcGivesExactCylinderPatch) {
  const double r = 1.7, height = 2.5;
  const auto s = extrude<2>(quarter_arc(r), Eigen::Vector3d(0, 0, height));
  for (const auto& u : test::random_params(s, 300, 1)) {
    Eigen::Vector3d x;
    s.eval(u, x.data());
    EXPECT_NEAR(std::hypot(x.x(), x.y()), r, 1e-12);
    EXPECT_NEAR(x.z(), u[1] * height, 1e-12);
  }
}

TEST(Extrude, QuarterDiscAndAnnulusSectorsGiveExactRadiiAndVolume) {
  // r0 = 0: the disc sector, whose inner arc collapses to the centre.
  for (double r0 : {0.0, 0.6}) extrude_sector(r0, 2.1, 1.3);
}

TEST(ExtrudeAlong, SurfacePlusPathIsExactForRationalInputs) {
  const auto base = test::random_spline<2>({2, 3}, {3, 2}, 3, true, 3);
  const auto path = test::random_spline<1>({3}, {4}, 3, true, 4);
  const auto vol = extrude_along<3>(base, path);
  std::vector<double> x(3), c(3), c0(3), v(3);
  path.eval({path.knots(0).start()}, c0.data());
  for (const auto& u : test::random_params(vol, 300, 5)) {
    base.eval({u[0], u[1]}, x.data());
    path.eval({u[2]}, c.data());
    vol.eval(u, v.data());
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(v[d], x[d] + c[d] - c0[d], 1e-12);
  }
}

TEST(ExtrudeAlong, CurvePlusPathGivesTranslationalSurface) {
  const auto base = test::random_spline<1>({2}, {3}, 2, false, 6);
  const auto path = test::random_spline<1>({3}, {2}, 2, true, 7, false);
  const auto s = extrude_along<2>(base, path);
  std::vector<double> x(2), c(2), c0(2), v(2);
  path.eval({path.knots(0).start()}, c0.data());
  for (const auto& u : test::random_params(s, 300, 8)) {
    base.eval({u[0]}, x.data());
    path.eval({u[1]}, c.data());
    s.eval(u, v.data());
    for (int d = 0; d < 2; ++d) EXPECT_NEAR(v[d], x[d] + c[d] - c0[d], 1e-12);
  }
}

TEST(Extrude, InvalidInputThrows) {
  EXPECT_THROW(extrude<2>(quarter_arc(1), Eigen::Vector2d(0, 1)), Error);
  EXPECT_THROW(extrude_along<2>(quarter_arc(1), test::random_spline<1>({2}, {2}, 2, false, 1)), Error);
}
