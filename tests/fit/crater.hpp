#pragma once
// The fit tests' terrain: a tilted plane with a crater, a bowl of radius kR around (kCx, kCy) whose rim is a sharp
// ridge (a kink at r = kR), so refinement must stay local to the rim.
#include <cmath>

namespace trivar::test {

inline constexpr double kCx = 0.3, kCy = 0.6, kR = 0.12;

inline double crater(double x, double y) {
  const double r = std::hypot(x - kCx, y - kCy);
  const double plane = 0.1 * x + 0.05 * y;
  if (r < kR) return plane - 0.2 * (1 - (r / kR) * (r / kR)) + 0.08 * (r / kR) * (r / kR) * (r / kR);
  return plane + 0.08 * std::exp(-(r - kR) / 0.02);
}

}  // namespace trivar::test
