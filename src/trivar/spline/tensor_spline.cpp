#include "trivar/spline/tensor_spline.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "trivar/core/error.hpp"
#include "trivar/core/parallel.hpp"
#include "trivar/core/scratch.hpp"
#include "trivar/spline/basis.hpp"
#include "trivar/spline/derivative_index.hpp"

namespace trivar {

namespace {

// Sum over the active (p+1)^D block of control values, weighted by the tensor product of N[k]:
// acc[0..st) += sum_i prod_k N[k][i_k] * c(first + i). ST > 0 fixes the stride at compile time for the
// common control dimensions so the innermost loop unrolls.
template <int L, int ST, int D>
inline void contract(const double* base, const std::array<std::size_t, D>& step, const std::array<int, D>& len,
                     const std::array<const double*, D>& N, double w, int st, double* acc) {
  if constexpr (L == 0) {
    const int s = ST > 0 ? ST : st;
    for (int a = 0; a < len[0]; ++a) {
      const double c = w * N[0][a];
      const double* p = base + static_cast<std::size_t>(a) * s;
      for (int d = 0; d < s; ++d) acc[d] += c * p[d];
    }
  } else {
    for (int a = 0; a < len[L]; ++a)
      contract<L - 1, ST, D>(base + a * step[L], step, len, N, w * N[L][a], st, acc);
  }
}

template <int D>
inline void contract_dispatch(const double* base, const std::array<std::size_t, D>& step,
                              const std::array<int, D>& len, const std::array<const double*, D>& N, int st,
                              double* acc) {
  std::fill(acc, acc + st, 0.0);
  switch (st) {
    case 1: contract<D - 1, 1, D>(base, step, len, N, 1.0, st, acc); break;
    case 2: contract<D - 1, 2, D>(base, step, len, N, 1.0, st, acc); break;
    case 3: contract<D - 1, 3, D>(base, step, len, N, 1.0, st, acc); break;
    case 4: contract<D - 1, 4, D>(base, step, len, N, 1.0, st, acc); break;
    default: contract<D - 1, 0, D>(base, step, len, N, 1.0, st, acc); break;
  }
}

// Multi-indices up to kMaxDerivativeOrder; graded, so the table for any lower order is a prefix of it.
template <int D>
const std::vector<std::array<int, D>>& derivative_table() {
  static const std::vector<std::array<int, D>> table = derivative_multi_indices<D>(kMaxDerivativeOrder);
  return table;
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
    require(std::isfinite(coefs_[i]), "spline: coefficient value " + std::to_string(i) + " is not finite");
  if (rational_)
    for (int i = 0; i < num_coefs(); ++i)
      require(weight(i) > 0.0, "spline: weight of control point " + std::to_string(i) + " is " +
                                   std::to_string(weight(i)) + "; weights must be positive");
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
    basis_values(kv.data(), p, s, uk, N[k]);
    Np[k] = N[k];
    len[k] = p + 1;
    step[k] = stride_k;
    offset += static_cast<std::size_t>(s - p) * stride_k;
    stride_k *= static_cast<std::size_t>(kv.size());
  }
  const int st = stride();
  if (!rational_) {
    contract_dispatch<D>(coefs_.data() + offset, step, len, Np, st, out);
    return;
  }
  double small[8];
  double* acc = st <= 8 ? small : scratch(st);
  contract_dispatch<D>(coefs_.data() + offset, step, len, Np, st, acc);
  const double inv = 1.0 / acc[dim_];
  for (int d = 0; d < dim_; ++d) out[d] = acc[d] * inv;
}

template <int D>
void TensorSpline<D>::eval_derivs(const Param<D>& u, int order, double* out) const {
  require(order >= 0 && order <= kMaxDerivativeOrder,
          "spline: derivative order " + std::to_string(order) + " is outside [0, " +
              std::to_string(kMaxDerivativeOrder) + "]");
  const int st = stride();
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
  for (int a = 0; a < nd; ++a) {
    std::array<const double*, D> Np;
    for (int k = 0; k < D; ++k)
      Np[k] = ders + static_cast<std::size_t>(k) * (order + 1) * (kMaxDegree + 1) + table[a][k] * len[k];
    contract_dispatch<D>(coefs_.data() + offset, step, len, Np, st, h + static_cast<std::size_t>(a) * st);
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
      basis_values(kv.data(), p, s, uk, basis[k].data() + q * (p + 1));
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
      next.assign(mk * post * row, 0.0);
      dst = next.data();
    }
    parallel_for(static_cast<std::ptrdiff_t>(mk * post), threads, [&](std::ptrdiff_t r) {
      const std::size_t q = static_cast<std::size_t>(r) % mk, o = static_cast<std::size_t>(r) / mk;
      double* d = dst + (q + mk * o) * row;
      std::fill(d, d + row, 0.0);
      const double* N = basis[k].data() + q * len;
      const double* s = src + (first[k][q] + nk * o) * row;
      for (int a = 0; a < len; ++a)
        for (std::size_t x = 0; x < row; ++x) d[x] += N[a] * s[a * row + x];
    });
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
