#pragma once
// One-sided finite differences for measuring derivative jumps across seams, each side sampled on its own patch
// or block only (independent of how the stitching computes its conditions).
#include <cmath>

#include <Eigen/Dense>

namespace trivar {

// Weights of the one-sided derivative at 0 from samples at 0, s h, ..., 7 s h (s = +-1): exact for polynomials of
// degree 7 (a Vandermonde system).
inline Eigen::VectorXd stencil_weights(double h, double s) {
  constexpr int n = 8;
  Eigen::MatrixXd V(n, n);
  Eigen::VectorXd e = Eigen::VectorXd::Zero(n);
  e[1] = 1;
  for (int m = 0; m < n; ++m)
    for (int k = 0; k < n; ++k) V(m, k) = std::pow(s * k * h, m);
  return V.fullPivLu().solve(e);
}

}  // namespace trivar
