#pragma once
// Small dense tensor kernels on the (p_0+1) x ... x (p_{D-1}+1) local B-splines of one cell: applying a
// Kronecker product of 1-D square matrices (local refinement, Bezier extraction) to coefficient vectors, and the
// Bernstein polynomials of a cell with their derivatives.
#include <algorithm>
#include <array>
#include <vector>

#include "trivar/core/box.hpp"
#include "trivar/spline/basis.hpp"

namespace trivar {

// v[b] <- sum_a prod_k M_k[a_k n_k + b_k] v[a] for `count` vectors of prod(n) x stride values each (local index
// u fastest, then the stride components); tmp is scratch.
template <int D>
void apply_kronecker(const Ints<D>& n, const std::array<const double*, D>& M, int stride, int count, double* v,
                     std::vector<double>& tmp) {
  int size = stride;
  for (int k = 0; k < D; ++k) size *= n[k];
  tmp.resize(static_cast<std::size_t>(size));
  for (int r = 0; r < count; ++r) {
    double* x = v + static_cast<std::ptrdiff_t>(r) * size;
    int inner = stride;
    for (int k = 0; k < D; ++k) {
      const int nk = n[k], outer = size / (inner * nk);
      const double* m = M[k];
      for (int o = 0; o < outer; ++o)
        for (int b = 0; b < nk; ++b) {
          double* dst = tmp.data() + (o * nk + b) * inner;
          std::fill(dst, dst + inner, 0.0);
          for (int a = 0; a < nk; ++a) {
            const double f = m[a * nk + b];
            if (f == 0.0) continue;
            const double* src = x + (o * nk + a) * inner;
            for (int s = 0; s < inner; ++s) dst[s] += f * src[s];
          }
        }
      std::copy(tmp.begin(), tmp.begin() + size, x);
      inner *= nk;
    }
  }
}

// Bernstein polynomials of degree p on [lo, hi] at x and their derivatives up to order n:
// out[o * (p + 1) + i] = d^o/dx^o of polynomial i (orders above p are zero).
inline void bernstein_derivatives(int p, double lo, double hi, double x, int n, double* out) {
  double t[2 * (kMaxDegree + 1)];
  std::fill(t, t + p + 1, lo);
  std::fill(t + p + 1, t + 2 * p + 2, hi);
  basis_derivatives(t, p, p, x, n, out);
}

}  // namespace trivar
