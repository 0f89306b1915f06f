#include "trivar/model/cylinder.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "support/spline_fixtures.hpp"
#include "trivar/core/error.hpp"
#include "trivar/spline/iso_extraction.hpp"
#include "trivar/spline/jacobian.hpp"
#include "trivar/spline/measure.hpp"

using namespace trivar;

TEST(Cylinder, VolumeIsPiR2H) {
  const double r = 1.3, h = 2.1;
  const auto cells = make_cylinder({.radius = r, .height = h});
  ASSERT_EQ(cells.size(), 5u);
  double v = 0;
  for (const auto& c : cells) v += signed_measure(c, 12);
  EXPECT_NEAR(v / (std::numbers::pi * r * r * h), 1.0, 1e-9);
}

TEST(Cylinder, EveryCellCertifiedValidOverCoreRange) {
  for (const double core : {0.1, 0.6, 0.95})
    for (const auto& c : make_cylinder({.radius = 0.7, .height = 0.3, .core = core})) {
      const auto rep = check_jacobian(c);
      EXPECT_TRUE(rep.valid) << "core " << core << " min lower bound " << rep.min_lower_bound;
    }
}

TEST(Cylinder, LateralBoundaryAtExactRadius) {
  const double r = 1.3, h = 2.1;
  const auto cells = make_cylinder({.radius = r, .height = h});
  double worst = 0;
  for (int c = 1; c <= 4; ++c) {
    const auto face = iso_extract(cells[c], 1, 1.0);  // disk v = 1: the arc
    for (const auto& u : test::random_params(face, 500, 10 + c)) {
      double x[3];
      face.eval(u, x);
      worst = std::max(worst, std::abs(std::hypot(x[0], x[1]) - r));
      ASSERT_GE(x[2], -1e-15);
      ASSERT_LE(x[2], h + 1e-15);
    }
  }
  EXPECT_LE(worst, 1e-12);
}

TEST(Cylinder, InvalidDimensionsThrow) {
  EXPECT_THROW(make_cylinder({.radius = -1, .height = 1}), Error);
  EXPECT_THROW(make_cylinder({.radius = 1, .height = 0}), Error);
  EXPECT_THROW(make_cylinder({.radius = 1, .height = 1, .core = 1.0}), Error);
  EXPECT_THROW(make_cylinder({.radius = 1, .height = 1, .core = 0.0}), Error);
  EXPECT_THROW(make_cylinder({.radius = std::nan(""), .height = 1}), Error);
}
