#include "trivar/spline/element_polynomials.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "trivar/spline/simd_level.hpp"

namespace trivar {

namespace element_polynomials {

// Four lanes: x, y, z and the weight (or zeros), one 256-bit vector with AVX2, two SSE2 vectors otherwise.
typedef double V4 __attribute__((vector_size(32)));
// V4 never crosses a call boundary (the body is inlined into each entry point).
#pragma GCC diagnostic ignored "-Wpsabi"

[[gnu::always_inline]] inline V4 load4(const double* p) {
  V4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// Horner's rule in x0 on each of the P1 + 1 rows of one x2 slice of the block (independent chains), then in x1
// over the rows. The slices are combined by Horner's rule in x2 with the run-time last degree (a loop of at
// most 5 steps around the unrolled slice), which keeps the kernels to one per (P0, P1) pair.
template <int P0, int P1>
[[gnu::always_inline]] inline V4 slice_value(const double* c, const double* x) {
  V4 acc1{};
#pragma GCC unroll 8
  for (int m1 = P1; m1 >= 0; --m1) {
    const double* row = c + m1 * (P0 + 1) * 4;
    V4 acc0 = load4(row + 4 * P0);
#pragma GCC unroll 8
    for (int m0 = P0 - 1; m0 >= 0; --m0) acc0 = acc0 * x[0] + load4(row + 4 * m0);
    acc1 = m1 == P1 ? acc0 : acc1 * x[1] + acc0;
  }
  return acc1;
}

template <int P0, int P1>
[[gnu::always_inline]] inline void horner3(const double* c, int p2, const double* x, double* h) {
  constexpr int kSlice = (P0 + 1) * (P1 + 1) * 4;
  V4 acc2 = slice_value<P0, P1>(c + p2 * kSlice, x);
  for (int m2 = p2 - 1; m2 >= 0; --m2) acc2 = acc2 * x[2] + slice_value<P0, P1>(c + m2 * kSlice, x);
  std::memcpy(h, &acc2, sizeof acc2);
}

// The same with the partial derivatives in x0, x1 (and x2): Horner's rule carries each derivative beside the
// value (d = d x + v before v = v x + c). h gets 4 lanes of the value, then 4 per derivative.
template <int P0, int P1>
[[gnu::always_inline]] inline void slice_first(const double* c, const double* x, V4& v1, V4& d10, V4& d11) {
  v1 = d10 = d11 = V4{};
#pragma GCC unroll 8
  for (int m1 = P1; m1 >= 0; --m1) {
    const double* row = c + m1 * (P0 + 1) * 4;
    V4 v0 = load4(row + 4 * P0), d00{};
#pragma GCC unroll 8
    for (int m0 = P0 - 1; m0 >= 0; --m0) {
      d00 = d00 * x[0] + v0;
      v0 = v0 * x[0] + load4(row + 4 * m0);
    }
    d11 = d11 * x[1] + v1;
    v1 = v1 * x[1] + v0;
    d10 = d10 * x[1] + d00;
  }
}

template <int P0, int P1>
[[gnu::always_inline]] inline void horner3_first(const double* c, int p2, const double* x, double* h) {
  constexpr int kSlice = (P0 + 1) * (P1 + 1) * 4;
  V4 v2, d20, d21, d22{};
  slice_first<P0, P1>(c + p2 * kSlice, x, v2, d20, d21);
  for (int m2 = p2 - 1; m2 >= 0; --m2) {
    V4 v1, d10, d11;
    slice_first<P0, P1>(c + m2 * kSlice, x, v1, d10, d11);
    d22 = d22 * x[2] + v2;
    v2 = v2 * x[2] + v1;
    d20 = d20 * x[2] + d10;
    d21 = d21 * x[2] + d11;
  }
  std::memcpy(h, &v2, sizeof v2);
  std::memcpy(h + 4, &d20, sizeof d20);
  std::memcpy(h + 8, &d21, sizeof d21);
  std::memcpy(h + 12, &d22, sizeof d22);
}

}  // namespace element_polynomials

// The point kernels: locate the element (on uniform knots by one multiplication, as the B-spline kernels do),
// Horner's rule on its block, divide by the weight lane.
template <int P0, int P1>
struct ElementKernel {
  // The element's coefficient block; x gets the local coordinates, scale d x_k / d u_k.
  [[gnu::always_inline]] static const double* locate(const ElementPolynomials& e, const Param<3>& u, double* x,
                                                     double* scale) {
    std::size_t offset = 0;
#pragma GCC unroll 3
    for (int k = 0; k < 3; ++k) {
      const ElementPolynomials::Axis& a = e.axes_[k];
      const double uk = std::clamp(u[k], a.lo, a.hi);
      const int s = a.inv_h > 0.0 ? static_cast<int>(std::clamp((uk - a.lo) * a.inv_h, 0.0, a.last)) : e.search(k, uk);
      const double* b = e.local_.data() + a.local + 2 * static_cast<std::size_t>(s);
      x[k] = (uk - b[0]) * b[1];
      scale[k] = b[1];
      offset += static_cast<std::size_t>(s) * a.step;
    }
    return e.coefs_.data() + offset;
  }
  [[gnu::always_inline]] static void value(const ElementPolynomials& e, const Param<3>& u, double* out) {
    double x[3], scale[3], h[4];
    element_polynomials::horner3<P0, P1>(locate(e, u, x, scale), e.degrees_[2], x, h);
    const double inv = 1.0 / h[3];
    if (e.dim_ == 3) {  // the common case without the loop's vectorised prologue and epilogue
      out[0] = h[0] * inv;
      out[1] = h[1] * inv;
      out[2] = h[2] * inv;
      return;
    }
    for (int d = 0; d < e.dim_; ++d) out[d] = h[d] * inv;
  }
  // Quotient rule on the homogeneous value and derivatives (the weight lane of a polynomial is 1, its
  // derivatives 0).
  [[gnu::always_inline]] static void first(const ElementPolynomials& e, const Param<3>& u, double* out) {
    double x[3], scale[3], h[16];
    element_polynomials::horner3_first<P0, P1>(locate(e, u, x, scale), e.degrees_[2], x, h);
    const double inv = 1.0 / h[3];
    const int dim = e.dim_;
    for (int d = 0; d < dim; ++d) out[d] = h[d] * inv;
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < dim; ++d)
        out[(k + 1) * dim + d] = (h[4 * (k + 1) + d] - out[d] * h[4 * (k + 1) + 3]) * inv * scale[k];
  }
  static void generic_value(const ElementPolynomials& e, const Param<3>& u, double* out) { value(e, u, out); }
  static void generic_first(const ElementPolynomials& e, const Param<3>& u, double* out) { first(e, u, out); }
#if defined(__x86_64__)
  [[gnu::target("avx2,fma")]] static void avx2_value(const ElementPolynomials& e, const Param<3>& u, double* out) {
    value(e, u, out);
  }
  [[gnu::target("avx2,fma")]] static void avx2_first(const ElementPolynomials& e, const Param<3>& u, double* out) {
    first(e, u, out);
  }
#endif
  static std::array<ElementPolynomials::Kernel, 2> at(SimdLevel level) {
#if defined(__x86_64__)
    if (level != SimdLevel::generic) return {&avx2_value, &avx2_first};
#endif
    (void)level;
    return {&generic_value, &generic_first};
  }
};

namespace element_polynomials {

using Kernels = std::array<ElementPolynomials::Kernel, 2>;

// Degrees (P, P) and (P, 1) in the first two directions.
template <int P>
Kernels kernel_for_second(int p1, SimdLevel level) {
  if (p1 == P) return ElementKernel<P, P>::at(level);
  if (p1 == 1) return ElementKernel<P, 1>::at(level);
  return {};
}

Kernels kernel_for(int p0, int p1, SimdLevel level) {
  switch (p0) {
    case 1: return kernel_for_second<1>(p1, level);
    case 2: return kernel_for_second<2>(p1, level);
    case 3: return kernel_for_second<3>(p1, level);
    case 4: return kernel_for_second<4>(p1, level);
    default: return {};
  }
}

}  // namespace element_polynomials

ElementPolynomials::ElementPolynomials(const TensorSpline<3>& s, std::size_t max_bytes) {
  using namespace element_polynomials;
  const int p[3] = {s.degree(0), s.degree(1), s.degree(2)};
  if (s.dim() > 3 || s.stride() > 4) return;
  for (int k = 0; k < 3; ++k)
    if (p[k] < 1 || p[k] > KnotVector::kMaxPowerFormDegree || s.knots(k).power_forms() == nullptr) return;
  const int L[3] = {p[0] + 1, p[1] + 1, p[2] + 1};
  const std::size_t block = static_cast<std::size_t>(4 * L[0] * L[1] * L[2]);
  int spans[3];
  std::size_t elements = 1;
  for (int k = 0; k < 3; ++k) {
    spans[k] = s.knots(k).last_span() - s.knots(k).first_span() + 1;
    elements *= static_cast<std::size_t>(spans[k]);
  }
  // Twice the table while the degrees are reduced (values and their rounding bounds).
  if (elements > max_bytes / sizeof(double) / block / 2) return;
  const int st = s.stride(), n0 = s.count(0), n1 = s.count(1);
  const auto cs = s.coefs();
  const bool rational = s.is_rational();
  // One element's block, direction by direction: t0[c][b][m0] = sum_a C0[m0][a] P[a][b][c], then direction 1,
  // then 2, where Ck[m][a] is the coefficient of x^m in the span's B-spline a (4 lanes per entry: coordinates
  // in lanes 0 .. dim-1, the weight in lane 3). With `absolute`, the same sums of absolute values: they bound
  // the rounding error of each coefficient.
  std::vector<double> t0(block), t1(block);
  auto contract = [&](const int* sp, bool absolute, double* out) {
    const double* C[3];
    for (int k = 0; k < 3; ++k) C[k] = s.knots(k).span_power_form(sp[k]) + 2;
    auto f = [absolute](double v) { return absolute ? std::abs(v) : v; };
    std::fill(t0.begin(), t0.end(), 0.0);
    std::fill(t1.begin(), t1.end(), 0.0);
    for (int c = 0; c < L[2]; ++c)
      for (int b = 0; b < L[1]; ++b)
        for (int a = 0; a < L[0]; ++a) {
          const std::size_t ctrl =
              static_cast<std::size_t>((sp[0] - p[0] + a) + n0 * ((sp[1] - p[1] + b) + n1 * (sp[2] - p[2] + c)));
          const double* v = cs.data() + ctrl * static_cast<std::size_t>(st);
          const double lanes[4] = {dim_ > 0 ? v[0] : 0.0, dim_ > 1 ? v[1] : 0.0, dim_ > 2 ? v[2] : 0.0,
                                   rational ? v[dim_] : 1.0};
          for (int m0 = 0; m0 < L[0]; ++m0)
            for (int d = 0; d < 4; ++d)
              t0[static_cast<std::size_t>(((c * L[1] + b) * L[0] + m0) * 4 + d)] +=
                  f(C[0][m0 * L[0] + a]) * f(lanes[d]);
        }
    for (int c = 0; c < L[2]; ++c)
      for (int m1 = 0; m1 < L[1]; ++m1)
        for (int b = 0; b < L[1]; ++b)
          for (int q = 0; q < 4 * L[0]; ++q)
            t1[static_cast<std::size_t>((c * L[1] + m1) * L[0] * 4 + q)] +=
                f(C[1][m1 * L[1] + b]) * t0[static_cast<std::size_t>((c * L[1] + b) * L[0] * 4 + q)];
    // out index ((m2 * L1 + m1) * L0 + m0) * 4 + lane
    for (int m2 = 0; m2 < L[2]; ++m2)
      for (int c = 0; c < L[2]; ++c)
        for (int q = 0; q < 4 * L[0] * L[1]; ++q)
          out[static_cast<std::size_t>(m2 * L[1] * L[0] * 4 + q)] +=
              f(C[2][m2 * L[2] + c]) * t1[static_cast<std::size_t>(c * L[1] * L[0] * 4 + q)];
    // A polynomial's weight lane: exactly the constant 1 (the contraction gives it to rounding).
    if (!rational)
      for (std::size_t q = 0; q < block / 4; ++q) out[4 * q + 3] = q == 0 ? 1.0 : 0.0;
  };
  dim_ = s.dim();
  std::vector<double> full(elements * block, 0.0), bound(elements * block, 0.0);
  // Exact degree reduction: a power whose coefficients are all within their rounding bounds of zero (in every
  // element and lane) is absent, as in a trilinear cube stored at degree 4 (the ball's core); dropping them
  // changes values by no more than the contraction's own rounding.
  constexpr double kNoise = 40 * std::numeric_limits<double>::epsilon();
  int r[3] = {1, 1, 1};
  std::size_t e = 0;
  for (int e2 = 0; e2 < spans[2]; ++e2)
    for (int e1 = 0; e1 < spans[1]; ++e1)
      for (int e0 = 0; e0 < spans[0]; ++e0, ++e) {
        const int sp[3] = {s.knots(0).first_span() + e0, s.knots(1).first_span() + e1, s.knots(2).first_span() + e2};
        double* v = full.data() + e * block;
        double* w = bound.data() + e * block;
        contract(sp, false, v);
        contract(sp, true, w);
        for (int m2 = 0; m2 < L[2]; ++m2)
          for (int m1 = 0; m1 < L[1]; ++m1)
            for (int m0 = 0; m0 < L[0]; ++m0)
              for (int d = 0; d < 4; ++d) {
                const std::size_t q = static_cast<std::size_t>(((m2 * L[1] + m1) * L[0] + m0) * 4 + d);
                if (std::abs(v[q]) > kNoise * w[q]) {
                  r[0] = std::max(r[0], m0);
                  r[1] = std::max(r[1], m1);
                  r[2] = std::max(r[2], m2);
                }
              }
      }
  // Kernels exist for a second degree equal to the first or 1; otherwise both take the larger.
  if (r[1] != 1 && r[1] != r[0]) r[0] = r[1] = std::max(r[0], r[1]);
  const auto kernels = kernel_for(r[0], r[1], simd_level());
  if (!kernels[0]) return;
  const int R[3] = {r[0] + 1, r[1] + 1, r[2] + 1};
  const std::size_t reduced = static_cast<std::size_t>(4 * R[0] * R[1] * R[2]);
  knots_ = s.knot_vectors();
  std::size_t step = reduced;
  for (int k = 0; k < 3; ++k) {
    const KnotVector& kv = knots_[k];
    axes_[k] = {kv.start(), kv.end(), kv.uniform_inverse_spacing(), static_cast<double>(spans[k] - 1),
                local_.size(), step};
    step *= static_cast<std::size_t>(spans[k]);
    for (int sp = kv.first_span(); sp <= kv.last_span(); ++sp)
      local_.insert(local_.end(), kv.span_power_form(sp), kv.span_power_form(sp) + 2);
  }
  // The powers kept; a degree raised to the other direction's has zero coefficients above the spline's.
  coefs_.assign(elements * reduced, 0.0);
  for (e = 0; e < elements; ++e)
    for (int m2 = 0; m2 < R[2]; ++m2)
      for (int m1 = 0; m1 < std::min(R[1], L[1]); ++m1)
        for (int m0 = 0; m0 < std::min(R[0], L[0]); ++m0)
          for (int d = 0; d < 4; ++d)
            coefs_[e * reduced + static_cast<std::size_t>(((m2 * R[1] + m1) * R[0] + m0) * 4 + d)] =
                full[e * block + static_cast<std::size_t>(((m2 * L[1] + m1) * L[0] + m0) * 4 + d)];
  degrees_ = {r[0], r[1], r[2]};
  value_ = kernels[0];
  first_ = kernels[1];
}

}  // namespace trivar
