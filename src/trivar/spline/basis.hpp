#pragma once
// B-spline basis functions and their derivatives at one parameter: the p+1 functions that are non-zero on
// span s (t_s <= u < t_{s+1}), by the triangular Cox-de Boor scheme (Piegl & Tiller A2.2, A2.3).
// Allocation-free: scratch lives on the stack, bounded by kMaxDegree.
#include <algorithm>

#include "trivar/spline/knot_vector.hpp"

namespace trivar {

inline constexpr int kMaxDegree = 31;

// The triangular scheme. P >= 0 fixes the degree at compile time (loops unroll in the specialised evaluation
// kernels), P = -1 takes p. With kInverse the knot differences come as precomputed reciprocals `inv`
// (KnotVector::inverse_differences), so per-point evaluation only multiplies.
template <int P, bool kInverse>
inline void basis_values_impl(const double* t, int p_runtime, int s, double u, const double* inv, double* N) {
  const int p = P >= 0 ? P : p_runtime;
  double left[(P >= 0 ? P : kMaxDegree) + 1], right[(P >= 0 ? P : kMaxDegree) + 1];
  N[0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = u - t[s + 1 - j];
    right[j] = t[s + j] - u;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double tmp = kInverse ? N[r] * *inv++ : N[r] / (right[r + 1] + left[j - r]);
      N[r] = saved + right[r + 1] * tmp;
      saved = left[j - r] * tmp;
    }
    N[j] = saved;
  }
}

// N[0..p] = B_{s-p,p}(u), ..., B_{s,p}(u) on the raw knot array t (any knot sequence, e.g. local knots).
inline void basis_values(const double* t, int p, int s, double u, double* N) {
  basis_values_impl<-1, false>(t, p, s, u, nullptr, N);
}

// The same on a KnotVector, using its precomputed reciprocal knot differences.
template <int P = -1>
inline void basis_values(const KnotVector& kv, int s, double u, double* N) {
  basis_values_impl<P, true>(kv.data(), kv.degree(), s, u, kv.inverse_differences(s), N);
}

// basis_values with the degree fixed at compile time for the common degrees 1 to 4, chosen at run time: the
// generic evaluation path of mixed-degree splines (e.g. 4 x 4 x 1 sphere shells) needs it per direction.
inline void basis_values_any(const KnotVector& kv, int s, double u, double* N) {
  switch (kv.degree()) {
    case 1: return basis_values<1>(kv, s, u, N);
    case 2: return basis_values<2>(kv, s, u, N);
    case 3: return basis_values<3>(kv, s, u, N);
    case 4: return basis_values<4>(kv, s, u, N);
    default: return basis_values(kv, s, u, N);
  }
}

// Values and first derivatives: N[0..p] and dN[0..p]. The derivative of B_{i,p} is
// p (B_{i,p-1}/(t_{i+p}-t_i) - B_{i+1,p-1}/(t_{i+p+1}-t_{i+1})), read off the degree p-1 stage of the same triangle.
template <int P = -1>
inline void basis_values_first_derivatives(const KnotVector& kv, int s, double u, double* N, double* dN) {
  const double* t = kv.data();
  const double* inv = kv.inverse_differences(s);
  const int p = P >= 0 ? P : kv.degree();
  double left[(P >= 0 ? P : kMaxDegree) + 1], right[(P >= 0 ? P : kMaxDegree) + 1];
  N[0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = u - t[s + 1 - j];
    right[j] = t[s + j] - u;
    if (j == p) {
      // N holds the p degree-(p-1) functions; inv the reciprocals t_{s+1+r} - t_{s+1-p+r} of this stage.
      double prev = 0.0;
      for (int r = 0; r < p; ++r) {
        const double a = N[r] * inv[r] * p;
        dN[r] = prev - a;
        prev = a;
      }
      dN[p] = prev;
    }
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double tmp = N[r] * *inv++;
      N[r] = saved + right[r + 1] * tmp;
      saved = left[j - r] * tmp;
    }
    N[j] = saved;
  }
  if (p == 0) dN[0] = 0.0;
}

// Bernstein polynomials of degree P (P < 0: p_runtime) at t in [0, 1]: B[i] = C(p,i) t^i (1-t)^(p-i), by the same
// triangle with knots 0 and 1. With dB, also their derivatives with respect to u where t = (u - a) h, h = 1/(b - a).
template <int P>
inline void bernstein_values(int p_runtime, double t, double h, double* B, double* dB) {
  const int p = P >= 0 ? P : p_runtime;
  const double s = 1.0 - t;
  B[0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    if (dB && j == p) {
      // d/du B_{i,p} = p h (B_{i-1,p-1} - B_{i,p-1}).
      dB[0] = -p * h * B[0];
      for (int i = 1; i < p; ++i) dB[i] = p * h * (B[i - 1] - B[i]);
      dB[p] = p * h * B[p - 1];
    }
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double tmp = B[r];
      B[r] = saved + s * tmp;
      saved = t * tmp;
    }
    B[j] = saved;
  }
  if (dB && p == 0) dB[0] = 0.0;
}

// ders[k*(p+1) + i] = d^k/du^k B_{s-p+i,p}(u) for k = 0..n (derivatives above p are zero).
inline void basis_derivatives(const double* t, int p, int s, double u, int n, double* ders) {
  double ndu[kMaxDegree + 1][kMaxDegree + 1];
  double left[kMaxDegree + 1], right[kMaxDegree + 1];
  double a[2][kMaxDegree + 1] = {};  // initialised: GCC cannot see that only written entries are read
  ndu[0][0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = u - t[s + 1 - j];
    right[j] = t[s + j] - u;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      ndu[j][r] = right[r + 1] + left[j - r];  // lower triangle: knot differences
      const double tmp = ndu[r][j - 1] / ndu[j][r];
      ndu[r][j] = saved + right[r + 1] * tmp;
      saved = left[j - r] * tmp;
    }
    ndu[j][j] = saved;
  }
  const int w = p + 1;
  for (int j = 0; j <= p; ++j) ders[j] = ndu[j][p];
  const int nk = std::min(n, p);
  for (int r = 0; r <= p; ++r) {
    int s1 = 0, s2 = 1;
    a[0][0] = 1.0;
    for (int k = 1; k <= nk; ++k) {
      double d = 0.0;
      const int rk = r - k, pk = p - k;
      if (r >= k) {
        a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
        d = a[s2][0] * ndu[rk][pk];
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = (r - 1 <= pk) ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rk + j];
        d += a[s2][j] * ndu[rk + j][pk];
      }
      if (r <= pk) {
        a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
        d += a[s2][k] * ndu[r][pk];
      }
      ders[k * w + r] = d;
      std::swap(s1, s2);
    }
  }
  double f = p;
  for (int k = 1; k <= nk; ++k) {
    for (int j = 0; j <= p; ++j) ders[k * w + j] *= f;
    f *= (p - k);
  }
  for (int k = nk + 1; k <= n; ++k)
    for (int j = 0; j <= p; ++j) ders[k * w + j] = 0.0;
}

}  // namespace trivar
