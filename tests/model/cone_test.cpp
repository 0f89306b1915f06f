#include "trivar/model/cone.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "support/spline_fixtures.hpp"
#include "trivar/core/error.hpp"
#include "trivar/spline/iso_extraction.hpp"
#include "trivar/spline/jacobian.hpp"
#include "trivar/spline/measure.hpp"

using namespace trivar;

TEST(Cone, FrustumVolume) {
  for (const auto& [r0, r1] : {std::pair{1.0, 0.4}, std::pair{0.5, 1.5}, std::pair{1.0, 0.01}}) {
    const double h = 1.7;
    double v = 0;
    for (const auto& c : make_cone({.bottom_radius = r0, .top_radius = r1, .height = h})) v += signed_measure(c, 12);
    EXPECT_NEAR(v / (std::numbers::pi * h * (r0 * r0 + r0 * r1 + r1 * r1) / 3), 1.0, 1e-9) << r0 << " " << r1;
  }
}

TEST(Cone, EveryCellCertifiedValid) {
  for (const auto& [r0, r1] : {std::pair{1.0, 0.4}, std::pair{0.5, 1.5}, std::pair{1.0, 0.01}})
    for (const auto& c : make_cone({.bottom_radius = r0, .top_radius = r1, .height = 0.8})) {
      const auto rep = check_jacobian(c);
      EXPECT_TRUE(rep.valid) << r0 << " " << r1 << " min lower bound " << rep.min_lower_bound;
    }
}

TEST(Cone, LateralBoundaryOnTheCone) {
  const double r0 = 1.2, r1 = 0.3, h = 0.9;
  const auto cells = make_cone({.bottom_radius = r0, .top_radius = r1, .height = h});
  double worst = 0;
  for (int c = 1; c <= 4; ++c) {
    const auto face = iso_extract(cells[c], 1, 1.0);
    for (const auto& u : test::random_params(face, 500, 20 + c)) {
      double x[3];
      face.eval(u, x);
      worst = std::max(worst, std::abs(std::hypot(x[0], x[1]) - (r0 + (r1 - r0) * x[2] / h)));
    }
  }
  EXPECT_LE(worst, 1e-12);
}

TEST(Cone, InvalidDimensionsThrow) {
  EXPECT_THROW(make_cone({.bottom_radius = 1, .top_radius = 0, .height = 1}), Error);  // apex: singular
  EXPECT_THROW(make_cone({.bottom_radius = -1, .top_radius = 1, .height = 1}), Error);
  EXPECT_THROW(make_cone({.bottom_radius = 1, .top_radius = 1, .height = -2}), Error);
  EXPECT_THROW(make_cone({.bottom_radius = 1, .top_radius = 1, .height = 1, .core = 1.5}), Error);
}
