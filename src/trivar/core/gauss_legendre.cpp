#include "trivar/core/gauss_legendre.hpp"

#include <cmath>
#include <numbers>

#include "trivar/core/error.hpp"

namespace trivar {

QuadratureRule gauss_legendre(int n) {
  require(n >= 1, "Gauss-Legendre: number of points must be >= 1, got " + std::to_string(n));
  QuadratureRule r;
  r.nodes.resize(n);
  r.weights.resize(n);
  for (int i = 0; i < n; ++i) {
    // Tricomi's initial guess for the i-th root on [-1, 1], descending.
    double z = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5)), dp = 1.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = z;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (z * p1 - p0) / (z * z - 1);
      const double dz = p1 / dp;
      z -= dz;
      if (std::abs(dz) < 1e-16) break;
    }
    r.nodes[i] = 0.5 * (1 - z);
    r.weights[i] = 1.0 / ((1 - z * z) * dp * dp);
  }
  return r;
}

}  // namespace trivar
