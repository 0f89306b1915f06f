#pragma once
// Support for the io tests: a temporary directory per test, random object lists and exact comparison.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <variant>
#include <vector>

#include "support/spline_fixtures.hpp"
#include "support/temp_dir.hpp"
#include "trivar/lr/any_lr_spline.hpp"
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

// The spline of a reader's result whose dimension the test knows.
template <int D>
const LRSpline<D>& as(const AnyLRSpline& s) {
  return std::get<LRSpline<D>>(s);
}

// A distinct interior knot of direction k (partial rectangles must end on mesh lines).
template <int D>
double mid_knot(const TensorSpline<D>& t, int k) {
  std::vector<double> v = t.knots(k).knots();
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v[v.size() / 2];
}

// s with the first occurrence of `from` replaced by `to` (a failure when there is none).
inline std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const std::size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return s.replace(at, from.size(), to);
}

// The whole file, byte for byte.
inline std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Bernstein polynomial i of degree p at t, from its closed form (the reference the writers' Bezier points are
// checked against).
inline double bernstein(int p, int i, double t) {
  double c = 1;
  for (int k = 1; k <= i; ++k) c = c * (p - i + k) / k;
  return c * std::pow(t, i) * std::pow(1 - t, p - i);
}

}  // namespace trivar::test
