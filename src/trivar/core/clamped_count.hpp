#pragma once
// A count (pieces of a tessellation, ...) from a real estimate, clamped to [lo, hi] before the conversion to int:
// a huge, infinite or NaN estimate (absurd coordinates in a file) gives hi instead of undefined behaviour.
#include <cmath>

namespace trivar {

inline int clamped_count(double estimate, int lo, int hi) {
  const double c = std::ceil(estimate);
  if (!(c < hi)) return hi;  // NaN too
  return c > lo ? static_cast<int>(c) : lo;
}

}  // namespace trivar
