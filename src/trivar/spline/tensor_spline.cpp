#include "trivar/spline/tensor_spline.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "trivar/core/error.hpp"
#include "trivar/core/number_format.hpp"
#include "trivar/core/parallel.hpp"
#include "trivar/core/scratch.hpp"
#include "trivar/spline/basis.hpp"
#include "trivar/spline/derivative_index.hpp"
#include "trivar/spline/eval_kernels.hpp"

namespace trivar {

namespace {

// Sum factorisation of one evaluation. The control values of the active block that share the indices
// i_1..i_{D-1} form one contiguous row of L = (p_0+1)*stride values. First the rows are combined with the
// weights prod_{k>=1} N_k[i_k] into acc[0..L) (a long, vectorisable axpy), then acc is reduced with N_0.
// LF > 0 fixes L at compile time for the common (degree, control dimension) pairs so the axpy unrolls.
template <int K, int LF, int D>
inline void accumulate_rows(const double* base, const std::array<std::size_t, D>& step,
                            const std::array<int, D>& len, const std::array<const double*, D>& N, double w, int L,
                            double* acc) {
  if constexpr (K == 0) {
    const int n = LF > 0 ? LF : L;
    for (int x = 0; x < n; ++x) acc[x] += w * base[x];
  } else {
    for (int a = 0; a < len[K]; ++a)
      accumulate_rows<K - 1, LF, D>(base + a * step[K], step, len, N, w * N[K][a], L, acc);
  }
}

template <int D, int LF>
void rows_kernel(const double* base, const std::array<std::size_t, D>& step, const std::array<int, D>& len,
                 const std::array<const double*, D>& N, int L, double* acc) {
  const int n = LF > 0 ? LF : L;
  for (int x = 0; x < n; ++x) acc[x] = 0.0;
  accumulate_rows<D - 1, LF, D>(base, step, len, N, 1.0, L, acc);
}

template <int D, std::size_t... Ls>
constexpr auto make_rows_table(std::index_sequence<Ls...>) {
  using Fn = void (*)(const double*, const std::array<std::size_t, D>&, const std::array<int, D>&,
                      const std::array<const double*, D>&, int, double*);
  return std::array<Fn, sizeof...(Ls)>{&rows_kernel<D, static_cast<int>(Ls)>...};
}

// acc[0..L) for rows of length L; L <= 32 dispatches to a kernel with L fixed at compile time.
template <int D>
inline void accumulate(const double* base, const std::array<std::size_t, D>& step, const std::array<int, D>& len,
                       const std::array<const double*, D>& N, int L, double* acc) {
  static constexpr auto table = make_rows_table<D>(std::make_index_sequence<33>{});
  table[L <= 32 ? L : 0](base, step, len, N, L, acc);
}

// out[0..st) = sum_a N0[a] * acc[a*st .. a*st+st).
inline void reduce_first(const double* acc, const double* N0, int len0, int st, double* out) {
  std::fill(out, out + st, 0.0);
  for (int a = 0; a < len0; ++a)
    for (int d = 0; d < st; ++d) out[d] += N0[a] * acc[a * st + d];
}

// Multi-indices up to kMaxDerivativeOrder; graded, so the table for any lower order is a prefix of it.
template <int D>
const std::vector<std::array<int, D>>& derivative_table() {
  static const std::vector<std::array<int, D>> table = derivative_multi_indices<D>(kMaxDerivativeOrder);
  return table;
}

// Rational evaluation divides by sums of weights and the Jacobian check raises them to the power D + 1, so the
// largest weight must keep those powers normal doubles; a weight far below the largest is numerically zero. A
// common factor of all weights leaves the geometry unchanged, so the bounds lose no model.
constexpr double kMinLargestWeight = 1e-50;
constexpr double kMinWeightRatio = 1e-12;

template <int D>
void validate_weights(const TensorSpline<D>& s) {
  int largest = 0;
  for (int i = 0; i < s.num_coefs(); ++i) {
    require(s.weight(i) > 0.0, [&] {
      return "spline: weight of control point " + std::to_string(i) + " is " + format_number(s.weight(i)) +
             "; weights must be positive";
    });
    if (s.weight(i) > s.weight(largest)) largest = i;
  }
  const double w_max = s.weight(largest);
  require(w_max >= kMinLargestWeight && w_max <= 1.0 / kMinLargestWeight, [&] {
    return "spline: the largest weight " + format_number(w_max) + " (control point " + std::to_string(largest) +
           ") is outside [" + format_number(kMinLargestWeight) + ", " + format_number(1.0 / kMinLargestWeight) +
           "]; scale all weights by a common factor, which leaves the geometry unchanged";
  });
  for (int i = 0; i < s.num_coefs(); ++i)
    require(s.weight(i) >= kMinWeightRatio * w_max, [&] {
      return "spline: weight of control point " + std::to_string(i) + " is " + format_number(s.weight(i)) +
             ", less than " + format_number(kMinWeightRatio) + " times the largest weight " + format_number(w_max) +
             " (control point " + std::to_string(largest) + ")";
    });
}

}  // namespace

template <int D>
TensorSpline<D>::TensorSpline(std::array<KnotVector, D> knots, int dim, bool rational, std::vector<double> coefs)
    : knots_(std::move(knots)), dim_(dim), rational_(rational), coefs_(std::move(coefs)) {
  require(dim_ >= 1, "spline: control dimension must be >= 1, got " + std::to_string(dim_));
  for (int k = 0; k < D; ++k)
    require(knots_[k].size() >= 1 && !knots_[k].knots().empty(),
            "spline: direction " + std::to_string(k) + " has no knot vector");
  const std::size_t expected = static_cast<std::size_t>(num_coefs()) * stride();
  require(coefs_.size() == expected, "spline: expected " + std::to_string(expected) + " coefficient values (" +
                                         std::to_string(num_coefs()) + " control points x " +
                                         std::to_string(stride()) + "), got " + std::to_string(coefs_.size()));
  for (std::size_t i = 0; i < coefs_.size(); ++i)
    if (!std::isfinite(coefs_[i])) throw Error("spline: coefficient value " + std::to_string(i) + " is not finite");
  const FixedKernels<D> k = fixed_kernels<D>(knots_, stride(), simd_level());
  fixed_ = k.value;
  fixed_d1_ = k.first;
  fixed_batch_ = k.batch;
  if (rational_) validate_weights(*this);
}

template <int D>
TensorSpline<D> TensorSpline<D>::from_cartesian(std::array<KnotVector, D> knots, int dim,
                                                std::span<const double> points, std::span<const double> weights) {
  std::size_t n = 1;
  for (int k = 0; k < D; ++k) n *= static_cast<std::size_t>(knots[k].size());
  require(dim >= 1, "spline: control dimension must be >= 1, got " + std::to_string(dim));
  require(points.size() == n * dim, "spline: expected " + std::to_string(n * dim) + " control point values, got " +
                                        std::to_string(points.size()));
  if (weights.empty()) return TensorSpline(std::move(knots), dim, false, {points.begin(), points.end()});
  require(weights.size() == n,
          "spline: expected " + std::to_string(n) + " weights, got " + std::to_string(weights.size()));
  std::vector<double> h(n * (dim + 1));
  for (std::size_t i = 0; i < n; ++i) {
    for (int d = 0; d < dim; ++d) h[i * (dim + 1) + d] = points[i * dim + d] * weights[i];
    h[i * (dim + 1) + dim] = weights[i];
  }
  return TensorSpline(std::move(knots), dim, true, std::move(h));
}

template <int D>
typename TensorSpline<D>::Index TensorSpline<D>::counts() const {
  Index n;
  for (int k = 0; k < D; ++k) n[k] = knots_[k].size();
  return n;
}

template <int D>
int TensorSpline<D>::num_coefs() const {
  int n = 1;
  for (int k = 0; k < D; ++k) n *= knots_[k].size();
  return n;
}

template <int D>
int TensorSpline<D>::linear_index(const Index& i) const {
  int l = 0;
  for (int k = D - 1; k >= 0; --k) l = l * knots_[k].size() + i[k];
  return l;
}

template <int D>
typename TensorSpline<D>::Index TensorSpline<D>::multi_index(int linear) const {
  Index i;
  for (int k = 0; k < D; ++k) {
    i[k] = linear % knots_[k].size();
    linear /= knots_[k].size();
  }
  return i;
}

template <int D>
void TensorSpline<D>::control_point(int linear, double* x) const {
  const double* c = coef(linear);
  const double w = weight(linear);
  for (int d = 0; d < dim_; ++d) x[d] = rational_ ? c[d] / w : c[d];
}

template <int D>
void TensorSpline<D>::control_bounds(double* lo, double* hi) const {
  std::fill(lo, lo + dim_, std::numeric_limits<double>::infinity());
  std::fill(hi, hi + dim_, -std::numeric_limits<double>::infinity());
  double* x = scratch(dim_);
  for (int i = 0; i < num_coefs(); ++i) {
    control_point(i, x);
    for (int d = 0; d < dim_; ++d) {
      lo[d] = std::min(lo[d], x[d]);
      hi[d] = std::max(hi[d], x[d]);
    }
  }
}

template <int D>
Box<D> TensorSpline<D>::domain() const {
  Box<D> b;
  for (int k = 0; k < D; ++k) {
    b.lo[k] = knots_[k].start();
    b.hi[k] = knots_[k].end();
  }
  return b;
}

template <int D>
void TensorSpline<D>::eval(const Param<D>& u, double* out) const {
  if (fixed_) {
    if (!rational_) return fixed_(knots_, coefs_.data(), u, out);
    double h[4];
    fixed_(knots_, coefs_.data(), u, h);
    const double inv = 1.0 / h[dim_];
    for (int d = 0; d < dim_; ++d) out[d] = h[d] * inv;
    return;
  }
  double N[D][kMaxDegree + 1];
  std::array<const double*, D> Np;
  std::array<int, D> len;
  std::array<std::size_t, D> step;
  std::size_t offset = 0, stride_k = static_cast<std::size_t>(stride());
  for (int k = 0; k < D; ++k) {
    const KnotVector& kv = knots_[k];
    const int p = kv.degree();
    const double uk = std::clamp(u[k], kv.start(), kv.end());
    const int s = kv.find_span(uk);
    basis_values_any(kv, s, uk, N[k]);
    Np[k] = N[k];
    len[k] = p + 1;
    step[k] = stride_k;
    offset += static_cast<std::size_t>(s - p) * stride_k;
    stride_k *= static_cast<std::size_t>(kv.size());
  }
  const int st = stride();
  const int L = len[0] * st;
  constexpr int kStack = 4 * (kMaxDegree + 1);
  double acc_stack[kStack], h_stack[4];
  double* acc = L <= kStack ? acc_stack : scratch(static_cast<std::size_t>(L) + st);
  accumulate<D>(coefs_.data() + offset, step, len, Np, L, acc);
  if (!rational_) {
    reduce_first(acc, N[0], len[0], st, out);
    return;
  }
  double* h = st <= 4 ? h_stack : acc + L;
  reduce_first(acc, N[0], len[0], st, h);
  const double inv = 1.0 / h[dim_];
  for (int d = 0; d < dim_; ++d) out[d] = h[d] * inv;
}

template <int D>
void TensorSpline<D>::eval_derivs(const Param<D>& u, int order, double* out) const {
  if (order < 0 || order > kMaxDerivativeOrder)
    throw Error("spline: derivative order " + std::to_string(order) + " is outside [0, " +
                std::to_string(kMaxDerivativeOrder) + "]");
  const int st = stride();
  if (order == 1 && fixed_d1_) {
    double h[(D + 1) * 4];
    fixed_d1_(knots_, coefs_.data(), u, h);
    if (!rational_) {
      std::copy(h, h + (D + 1) * st, out);
      return;
    }
    // Quotient rule: S = A / w, S' = (A' - w' S) / w.
    const double inv = 1.0 / h[dim_];
    for (int d = 0; d < dim_; ++d) out[d] = h[d] * inv;
    for (int k = 1; k <= D; ++k)
      for (int d = 0; d < dim_; ++d) out[k * dim_ + d] = (h[k * st + d] - h[k * st + dim_] * out[d]) * inv;
    return;
  }
  const int nd = derivative_count(D, order);
  // Per direction: rows of basis derivatives 0..order, each p+1 long.
  double* ders = scratch<1>(static_cast<std::size_t>(D) * (order + 1) * (kMaxDegree + 1));
  std::array<int, D> len;
  std::array<std::size_t, D> step;
  std::size_t offset = 0, stride_k = static_cast<std::size_t>(st);
  for (int k = 0; k < D; ++k) {
    const KnotVector& kv = knots_[k];
    const int p = kv.degree();
    const double uk = std::clamp(u[k], kv.start(), kv.end());
    const int s = kv.find_span(uk);
    basis_derivatives(kv.data(), p, s, uk, order, ders + static_cast<std::size_t>(k) * (order + 1) * (kMaxDegree + 1));
    len[k] = p + 1;
    step[k] = stride_k;
    offset += static_cast<std::size_t>(s - p) * stride_k;
    stride_k *= static_cast<std::size_t>(kv.size());
  }
  const auto& table = derivative_table<D>();
  double* h = rational_ ? scratch<2>(static_cast<std::size_t>(nd) * st) : out;
  // Row sums depend only on the derivative orders in directions 1..D-1 (the "tail" of the multi-index);
  // compute each tail once and reduce it with every derivative order of direction 0 that uses it.
  const int L = len[0] * st;
  double* acc = scratch<3>(static_cast<std::size_t>(L));
  auto row = [&](int k, int order_k) {
    return ders + static_cast<std::size_t>(k) * (order + 1) * (kMaxDegree + 1) + order_k * len[k];
  };
  for (int a = 0; a < nd; ++a) {
    if (table[a][0] != 0) continue;  // tails are the multi-indices with a_0 = 0
    std::array<const double*, D> Np;
    for (int k = 0; k < D; ++k) Np[k] = row(k, table[a][k]);
    accumulate<D>(coefs_.data() + offset, step, len, Np, L, acc);
    int tail_order = 0;
    for (int k = 1; k < D; ++k) tail_order += table[a][k];
    for (int a0 = 0; a0 + tail_order <= order; ++a0) {
      auto alpha = table[a];
      alpha[0] = a0;
      reduce_first(acc, row(0, a0), len[0], st, h + static_cast<std::size_t>(derivative_position<D>(alpha)) * st);
    }
  }
  if (!rational_) return;
  // Generalised quotient rule: S^(a) = (A^(a) - sum_{0 < b <= a} C(a,b) w^(b) S^(a-b)) / w.
  const double w0 = h[dim_];
  for (int a = 0; a < nd; ++a) {
    const auto& alpha = table[a];
    double* s = out + static_cast<std::size_t>(a) * dim_;
    for (int d = 0; d < dim_; ++d) s[d] = h[static_cast<std::size_t>(a) * st + d];
    for (int b = 1; b <= a; ++b) {
      const auto& beta = table[b];
      bool le = true;
      double c = 1.0;
      std::array<int, D> diff;
      for (int k = 0; k < D; ++k) {
        le = le && beta[k] <= alpha[k];
        diff[k] = alpha[k] - beta[k];
        c *= static_cast<double>(binomial(alpha[k], beta[k]));
      }
      if (!le) continue;
      const double f = c * h[static_cast<std::size_t>(b) * st + dim_];
      const double* prev = out + static_cast<std::size_t>(derivative_position<D>(diff)) * dim_;
      for (int d = 0; d < dim_; ++d) s[d] -= f * prev[d];
    }
    for (int d = 0; d < dim_; ++d) s[d] /= w0;
  }
}

template <int D>
void TensorSpline<D>::eval_batch(std::span<const Param<D>> u, std::span<double> out, int threads) const {
  require(out.size() >= u.size() * dim_, "spline: batch output buffer too small");
  if (fixed_batch_) {
    // Blocks of points per kernel call; the static split keeps every point on the same code for any thread count.
    constexpr std::size_t kBlock = 256;
    const std::size_t n = u.size(), blocks = (n + kBlock - 1) / kBlock;
    parallel_for(static_cast<std::ptrdiff_t>(blocks), threads, [&](std::ptrdiff_t b) {
      const std::size_t first = static_cast<std::size_t>(b) * kBlock;
      fixed_batch_(knots_, coefs_.data(), rational_, u.data() + first, std::min(kBlock, n - first),
                   out.data() + first * dim_);
    });
    return;
  }
  parallel_for(static_cast<std::ptrdiff_t>(u.size()), threads,
               [&](std::ptrdiff_t i) { eval(u[i], out.data() + i * dim_); });
}

template <int D>
void TensorSpline<D>::eval_derivs_batch(std::span<const Param<D>> u, int order, std::span<double> out,
                                        int threads) const {
  const std::size_t per = static_cast<std::size_t>(derivative_count(D, order)) * dim_;
  require(out.size() >= u.size() * per, "spline: batch output buffer too small");
  parallel_for(static_cast<std::ptrdiff_t>(u.size()), threads,
               [&](std::ptrdiff_t i) { eval_derivs(u[i], order, out.data() + i * per); });
}

template <int D>
void TensorSpline<D>::eval_grid(const std::array<std::vector<double>, D>& params, std::span<double> out,
                                int threads) const {
  std::size_t total = 1;
  for (int k = 0; k < D; ++k) total *= params[k].size();
  require(out.size() >= total * dim_, "spline: grid output buffer too small");
  if (total == 0) return;
  const int st = stride();
  std::array<std::vector<int>, D> first;
  std::array<std::vector<double>, D> basis;
  for (int k = 0; k < D; ++k) {
    const KnotVector& kv = knots_[k];
    const int p = kv.degree();
    first[k].resize(params[k].size());
    basis[k].resize(params[k].size() * (p + 1));
    for (std::size_t q = 0; q < params[k].size(); ++q) {
      const double uk = std::clamp(params[k][q], kv.start(), kv.end());
      const int s = kv.find_span(uk);
      first[k][q] = s - p;
      basis_values(kv, s, uk, basis[k].data() + q * (p + 1));
    }
  }
  // Contract the last direction first; the array keeps shape (n_0, .., n_{k-1}, m_k, .., m_{D-1}).
  std::array<std::size_t, D> shape;
  for (int k = 0; k < D; ++k) shape[k] = knots_[k].size();
  std::vector<double> cur, next;
  const double* src = coefs_.data();
  for (int k = D - 1; k >= 0; --k) {
    std::size_t pre = 1, post = 1;
    for (int j = 0; j < k; ++j) pre *= shape[j];
    for (int j = k + 1; j < D; ++j) post *= shape[j];
    const std::size_t nk = shape[k], mk = params[k].size();
    const int len = knots_[k].degree() + 1;
    const std::size_t row = pre * st;
    const bool direct = k == 0 && !rational_;
    double* dst;
    if (direct) {
      dst = out.data();
    } else {
      next.resize(mk * post * row);
      dst = next.data();
    }
    // Short rows (the last contraction: one control value per point) get compile-time row lengths.
    auto contract_axis = [&]<std::size_t RF>() {
      const std::size_t rl = RF > 0 ? RF : row;
      parallel_for(static_cast<std::ptrdiff_t>(mk * post), threads, [&](std::ptrdiff_t r) {
        const std::size_t q = static_cast<std::size_t>(r) % mk, o = static_cast<std::size_t>(r) / mk;
        double* d = dst + (q + mk * o) * rl;
        const double* N = basis[k].data() + q * len;
        const double* s = src + (first[k][q] + nk * o) * rl;
        for (std::size_t x = 0; x < rl; ++x) d[x] = N[0] * s[x];
        for (int a = 1; a < len; ++a)
          for (std::size_t x = 0; x < rl; ++x) d[x] += N[a] * s[a * rl + x];
      });
    };
    switch (row) {
      case 1: contract_axis.template operator()<1>(); break;
      case 3: contract_axis.template operator()<3>(); break;
      case 4: contract_axis.template operator()<4>(); break;
      default: contract_axis.template operator()<0>(); break;
    }
    shape[k] = mk;
    if (direct) return;
    cur.swap(next);
    src = cur.data();
  }
  parallel_for(static_cast<std::ptrdiff_t>(total), threads, [&](std::ptrdiff_t i) {
    const double* h = src + static_cast<std::size_t>(i) * st;
    const double inv = 1.0 / h[dim_];
    for (int d = 0; d < dim_; ++d) out[i * dim_ + d] = h[d] * inv;
  });
}

template class TensorSpline<1>;
template class TensorSpline<2>;
template class TensorSpline<3>;

}  // namespace trivar
