#pragma once
// Support for the io tests: a temporary directory per test, random object lists and exact comparison.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "support/spline_fixtures.hpp"
#include "support/temp_dir.hpp"
#include "trivar/spline/any_spline.hpp"

namespace trivar::test {

// Curves, surfaces and volumes of several degrees and control dimensions, clamped and unclamped.
inline std::vector<AnySpline> random_objects(bool rational, unsigned seed) {
  std::vector<AnySpline> out;
  for (int dim : {1, 2, 3, 5}) {
    out.emplace_back(random_spline<1>({1 + dim % 4}, {5}, dim, rational, seed++));
    out.emplace_back(random_spline<2>({2, 3}, {3, 4}, dim, rational, seed++, dim != 2));
    out.emplace_back(random_spline<3>({1, 2, 3}, {2, 3, 2}, dim, rational, seed++, dim != 3));
  }
  return out;
}

// Same type, knots, control dimension and homogeneous coefficients, compared with == (bit for bit; -0.0
// and 0.0 are told apart by the sign bit).
inline void expect_identical(const AnySpline& a, const AnySpline& b) {
  ASSERT_EQ(a.index(), b.index());
  std::visit(
      [&](const auto& x) {
        const auto& y = std::get<std::decay_t<decltype(x)>>(b);
        EXPECT_EQ(x.dim(), y.dim());
        EXPECT_EQ(x.is_rational(), y.is_rational());
        EXPECT_TRUE(x.knot_vectors() == y.knot_vectors());
        ASSERT_EQ(x.coefs().size(), y.coefs().size());
        for (std::size_t i = 0; i < x.coefs().size(); ++i) {
          EXPECT_EQ(x.coefs()[i], y.coefs()[i]) << "coefficient value " << i;
          EXPECT_EQ(std::signbit(x.coefs()[i]), std::signbit(y.coefs()[i])) << "coefficient value " << i;
        }
      },
      a);
}

}  // namespace trivar::test
