#include "trivar/core/gauss_legendre.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace trivar;

TEST(GaussLegendre, ExactForPolynomialsOfDegree2nMinus1) {
  for (int n = 1; n <= 12; ++n) {
    const auto r = gauss_legendre(n);
    for (int m = 0; m <= 2 * n - 1; ++m) {
      double s = 0;
      for (int i = 0; i < n; ++i) s += r.weights[i] * std::pow(r.nodes[i], m);
      EXPECT_NEAR(s, 1.0 / (m + 1), 1e-14) << "n=" << n << " m=" << m;
    }
    // One degree higher the error is the classical remainder (n!)^4 / ((2n+1) ((2n)!)^2) on [0, 1]; checked
    // while it is well above rounding.
    if (n <= 8) {
      double s = 0;
      for (int i = 0; i < n; ++i) s += r.weights[i] * std::pow(r.nodes[i], 2 * n);
      const double remainder = std::pow(std::tgamma(n + 1.0), 4) / ((2 * n + 1) * std::pow(std::tgamma(2 * n + 1.0), 2));
      EXPECT_NEAR((1.0 / (2 * n + 1) - s) / remainder, 1.0, 1e-5) << n;
    }
  }
  // Two points: 1/2 -+ 1/(2 sqrt 3).
  const auto r = gauss_legendre(2);
  EXPECT_NEAR(r.nodes[0], 0.5 - 0.5 / std::sqrt(3.0), 1e-15);
  EXPECT_NEAR(r.weights[1], 0.5, 1e-15);
}
