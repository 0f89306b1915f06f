#include "trivar/model/torus.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "support/spline_fixtures.hpp"
#include "trivar/core/error.hpp"
#include "trivar/spline/iso_extraction.hpp"
#include "trivar/spline/jacobian.hpp"
#include "trivar/spline/measure.hpp"

using namespace trivar;

TEST(Torus, VolumeIsTwoPi2RR2) {
  const double R = 2.5, r = 0.8;
  const auto cells = make_torus({.major_radius = R, .minor_radius = r});
  ASSERT_EQ(cells.size(), 5u);
  double v = 0;
  for (const auto& c : cells) v += signed_measure(c, 12);
  EXPECT_NEAR(v / (2 * std::numbers::pi * std::numbers::pi * R * r * r), 1.0, 1e-9);
}

TEST(Torus, EveryCellCertifiedValid) {
  for (const auto& c : make_torus({.major_radius = 1.0, .minor_radius = 0.9})) {
    const auto rep = check_jacobian(c);
    EXPECT_TRUE(rep.valid) << "min lower bound " << rep.min_lower_bound;
  }
}

TEST(Torus, BoundaryAtExactMinorRadius) {
  const double R = 2.5, r = 0.8;
  const auto cells = make_torus({.major_radius = R, .minor_radius = r});
  double worst = 0;
  for (int c = 1; c <= 4; ++c) {
    const auto face = iso_extract(cells[c], 1, 1.0);
    for (const auto& u : test::random_params(face, 500, 30 + c)) {
      double x[3];
      face.eval(u, x);
      worst = std::max(worst, std::abs(std::hypot(std::hypot(x[0], x[1]) - R, x[2]) - r));
    }
  }
  EXPECT_LE(worst, 1e-12);
}

TEST(Torus, InvalidDimensionsThrow) {
  EXPECT_THROW(make_torus({.major_radius = 1, .minor_radius = 1}), Error);
  EXPECT_THROW(make_torus({.major_radius = 1, .minor_radius = 2}), Error);
  EXPECT_THROW(make_torus({.major_radius = 1, .minor_radius = -0.5}), Error);
  EXPECT_THROW(make_torus({.major_radius = 2, .minor_radius = 0.5, .core = -0.1}), Error);
}
