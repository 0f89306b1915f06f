#pragma once
// The manufactured solution of the trimmed Poisson tests: u = sin(2x + 0.3) cos(y) e^z, for which -lap u = 4 u.
#include <cmath>

namespace trivar::test {

// u at x and, when g is not null, its gradient.
inline void sine_exp_solution(const double* x, double* u, double* g) {
  const double s = std::sin(2 * x[0] + 0.3), c = std::cos(2 * x[0] + 0.3), e = std::exp(x[2]);
  u[0] = s * std::cos(x[1]) * e;
  if (g) {
    g[0] = 2 * c * std::cos(x[1]) * e;
    g[1] = -s * std::sin(x[1]) * e;
    g[2] = u[0];
  }
}

}  // namespace trivar::test
