#pragma once
// Gauss-Legendre quadrature on [0, 1]: n nodes, exact for polynomials of degree 2n - 1.
#include <vector>

namespace trivar {

struct QuadratureRule {
  std::vector<double> nodes;    // increasing, in (0, 1)
  std::vector<double> weights;  // positive, summing to 1
};

// Nodes by Newton's method on the three-term Legendre recurrence (n >= 1).
QuadratureRule gauss_legendre(int n);

}  // namespace trivar
