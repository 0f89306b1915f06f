#pragma once
// The fit's per-point kernel, shared by least squares and MBA: the tensor Bernstein values of a point in its
// element, with the degree known at compile time where all degrees are equal and small (internal to fit/).
#include <algorithm>
#include <span>
#include <type_traits>

#include "trivar/core/box.hpp"
#include "trivar/fit/least_squares.hpp"
#include "trivar/spline/basis.hpp"

namespace trivar::fit_kernel {

// Tensor Bernstein values (direction 0 fastest) at u of the element with lower corner lo and reciprocal sides
// inv_h. P >= 0: every degree is P, known at compile time (the common case, a third of the fit's time otherwise).
template <int D, int P>
void tensor_bernstein(const Ints<D>& deg, const Param<D>& lo, const Param<D>& inv_h, const Param<D>& u, double* out) {
  double b[D][kMaxDegree + 1];
  for (int k = 0; k < D; ++k) {
    const double t = std::clamp((u[k] - lo[k]) * inv_h[k], 0.0, 1.0);
    bernstein_values<P>(deg[k], t, 1.0, b[k], nullptr);
  }
  int n = (P >= 0 ? P : deg[0]) + 1;
  std::copy(b[0], b[0] + n, out);
  for (int k = 1; k < D; ++k) {
    const int m = (P >= 0 ? P : deg[k]) + 1;
    for (int i = m - 1; i >= 0; --i)
      for (int j = 0; j < n; ++j) out[i * n + j] = b[k][i] * out[j];
    n *= m;
  }
}

template <int D>
Param<D> reciprocal_sides(const Box<D>& box) {
  Param<D> inv_h;
  for (int k = 0; k < D; ++k) inv_h[k] = 1.0 / (box.hi[k] - box.lo[k]);
  return inv_h;
}

// Calls f with std::integral_constant<int, P>: P the common degree when it is 1, 2 or 3, else -1.
template <int D, class F>
void with_degree(const Ints<D>& deg, F&& f) {
  const bool equal = std::all_of(deg.begin(), deg.end(), [&](int p) { return p == deg[0]; });
  if (equal && deg[0] == 1) f(std::integral_constant<int, 1>());
  else if (equal && deg[0] == 2) f(std::integral_constant<int, 2>());
  else if (equal && deg[0] == 3) f(std::integral_constant<int, 3>());
  else f(std::integral_constant<int, -1>());
}

inline std::span<const int> points_of(const PointsByElement& where, int e) {
  const auto first = static_cast<std::size_t>(where.offsets[static_cast<std::size_t>(e)]);
  const auto last = static_cast<std::size_t>(where.offsets[static_cast<std::size_t>(e) + 1]);
  return {where.points.data() + first, last - first};
}

}  // namespace trivar::fit_kernel
