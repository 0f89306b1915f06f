#pragma once
// Ordering of partial derivatives of a D-variate function: graded by total order, and within one order
// lexicographically descending in (a_0, a_1, ...). For D = 3 and order 2:
//   0: f   1: f_u 2: f_v 3: f_w   4: f_uu 5: f_uv 6: f_uw 7: f_vv 8: f_vw 9: f_ww
#include <array>
#include <vector>

namespace trivar {

inline constexpr int kMaxDerivativeOrder = 10;

constexpr long binomial(int n, int k) {
  if (k < 0 || k > n) return 0;
  long r = 1;
  for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
  return r;
}

// Number of multi-indices of D variables with total order <= order.
constexpr int derivative_count(int D, int order) { return static_cast<int>(binomial(order + D, D)); }

// Position of multi-index a in the ordering above.
template <int D>
constexpr int derivative_position(const std::array<int, D>& a) {
  int n = 0;
  for (int k = 0; k < D; ++k) n += a[k];
  int pos = n == 0 ? 0 : derivative_count(D, n - 1);
  int rest = n;
  for (int k = 0; k + 1 < D; ++k) {
    const int dims_left = D - k - 1;  // tuples of the remaining variables summing to m: C(m + dims_left - 1, dims_left - 1)
    for (int ak = a[k] + 1; ak <= rest; ++ak) pos += static_cast<int>(binomial(rest - ak + dims_left - 1, dims_left - 1));
    rest -= a[k];
  }
  return pos;
}

// All multi-indices up to the given total order, in the ordering above.
template <int D>
std::vector<std::array<int, D>> derivative_multi_indices(int order) {
  std::vector<std::array<int, D>> out;
  for (int n = 0; n <= order; ++n) {
    std::array<int, D> a{};
    // Enumerate tuples summing to n in descending lexicographic order.
    auto rec = [&](auto&& self, int k, int rest) -> void {
      if (k == D - 1) {
        a[k] = rest;
        out.push_back(a);
        return;
      }
      for (int v = rest; v >= 0; --v) {
        a[k] = v;
        self(self, k + 1, rest - v);
      }
    };
    rec(rec, 0, n);
  }
  return out;
}

}  // namespace trivar
