#include "trivar/spline/bernstein.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "trivar/core/error.hpp"
#include "trivar/core/scratch.hpp"
#include "trivar/spline/derivative_index.hpp"

namespace trivar {

namespace {

template <int D>
int count_of(const Ints<D>& n) {
  int c = 1;
  for (int k = 0; k < D; ++k) c *= n[k] + 1;
  return c;
}

template <int D>
Ints<D> strides_of(const Ints<D>& n) {
  Ints<D> s{};
  int acc = 1;
  for (int k = 0; k < D; ++k) {
    s[k] = acc;
    acc *= n[k] + 1;
  }
  return s;
}

// Calls f(flat, multi_index) for every coefficient of a net of degrees n, first variable fastest.
template <int D, class F>
void for_each_index(const Ints<D>& n, F&& f) {
  Ints<D> i{};
  const int total = count_of<D>(n);
  for (int flat = 0; flat < total; ++flat) {
    f(flat, i);
    for (int k = 0; k < D; ++k) {
      if (++i[k] <= n[k]) break;
      i[k] = 0;
    }
  }
}

// Calls f(in_base, out_base) for every line along `dir` of two nets that differ only in their degree in dir.
template <int D, class F>
void for_each_line(const Ints<D>& n_in, const Ints<D>& n_out, int dir, F&& f) {
  const Ints<D> s_in = strides_of<D>(n_in), s_out = strides_of<D>(n_out);
  Ints<D> across = n_in;
  across[dir] = 0;
  for_each_index<D>(across, [&](int, const Ints<D>& i) {
    int a = 0, b = 0;
    for (int k = 0; k < D; ++k) {
      a += i[k] * s_in[k];
      b += i[k] * s_out[k];
    }
    f(a, b);
  });
}

// C(n, 0..n); exact in double for the degrees a Jacobian reaches (C(n, i) < 2^53 up to n = 56).
std::vector<double> binomial_row(int n) {
  std::vector<double> r(n + 1, 1.0);
  for (int i = 1; i <= n; ++i) r[i] = r[i - 1] * (n - i + 1) / i;
  return r;
}

template <int D>
std::string degrees_text(const Ints<D>& n) {
  std::string s = "(";
  for (int k = 0; k < D; ++k) {
    if (k) s += ',';
    s += std::to_string(n[k]);
  }
  return s + ")";
}

// Sum over the tensor net of c_i prod_k B_k[i_k], one direction at a time from the slowest.
template <int D, int K>
double contract(const double* c, const Ints<D>& n, const Ints<D>& stride, const double* const* B) {
  double s = 0;
  for (int i = 0; i <= n[K]; ++i) {
    if constexpr (K == 0)
      s += B[0][i] * c[i];
    else
      s += B[K][i] * contract<D, K - 1>(c + i * stride[K], n, stride, B);
  }
  return s;
}

}  // namespace

template <int D>
Bernstein<D>::Bernstein(const Ints<D>& degrees, double value) : n_(degrees) {
  for (int k = 0; k < D; ++k)
    require(degrees[k] >= 0, [&] {
      return "Bernstein: negative degree " + std::to_string(degrees[k]) + " in direction " + std::to_string(k);
    });
  c_.assign(count_of<D>(n_), value);
}

template <int D>
Bernstein<D>::Bernstein(const Ints<D>& degrees, std::vector<double> coefs) : n_(degrees), c_(std::move(coefs)) {
  for (int k = 0; k < D; ++k)
    require(degrees[k] >= 0, [&] {
      return "Bernstein: negative degree " + std::to_string(degrees[k]) + " in direction " + std::to_string(k);
    });
  require(static_cast<int>(c_.size()) == count_of<D>(n_), [&] {
    return "Bernstein: " + std::to_string(c_.size()) + " coefficients given for degrees " + degrees_text<D>(n_) +
           ", expected " + std::to_string(count_of<D>(n_));
  });
}

template <int D>
int Bernstein<D>::index(const Ints<D>& i) const {
  int q = 0;
  for (int k = D - 1; k >= 0; --k) q = q * (n_[k] + 1) + i[k];
  return q;
}

template <int D>
double Bernstein<D>::eval(const Param<D>& t) const {
  int total = 0;
  for (int k = 0; k < D; ++k) total += n_[k] + 1;
  double* buf = scratch<4>(static_cast<std::size_t>(total));
  const double* B[D];
  double* b = buf;
  for (int k = 0; k < D; ++k) {
    // Powers built by multiplication: C(n,i) t^i (1-t)^(n-i).
    const int n = n_[k];
    const double x = t[k], y = 1.0 - t[k];
    double tp = 1.0;
    for (int i = 0; i <= n; ++i) {
      b[i] = static_cast<double>(binomial(n, i)) * tp;
      tp *= x;
    }
    double yp = 1.0;
    for (int i = n; i >= 0; --i) {
      b[i] *= yp;
      yp *= y;
    }
    B[k] = b;
    b += n + 1;
  }
  return contract<D, D - 1>(c_.data(), n_, strides_of<D>(n_), B);
}

template <int D>
double Bernstein<D>::min_coef() const {
  return *std::min_element(c_.begin(), c_.end());
}

template <int D>
double Bernstein<D>::max_coef() const {
  return *std::max_element(c_.begin(), c_.end());
}

template <int D>
double Bernstein<D>::corner(int corner) const {
  Ints<D> i{};
  for (int k = 0; k < D; ++k) i[k] = (corner >> k) & 1 ? n_[k] : 0;
  return c_[index(i)];
}

template <int D>
Bernstein<D> Bernstein<D>::elevate(const Ints<D>& to) const {
  Ints<D> by{};
  bool same = true;
  for (int k = 0; k < D; ++k) {
    require(to[k] >= n_[k], [&] {
      return "Bernstein::elevate: target degree " + std::to_string(to[k]) + " below degree " +
             std::to_string(n_[k]) + " in direction " + std::to_string(k);
    });
    by[k] = to[k] - n_[k];
    same = same && by[k] == 0;
  }
  if (same) return *this;
  // Raising the degree is multiplying by the constant 1 written with degrees `by`.
  return *this * Bernstein(by, 1.0);
}

template <int D>
Bernstein<D> Bernstein<D>::derivative(int dir) const {
  const int n = n_[dir];
  Ints<D> m = n_;
  m[dir] = std::max(n - 1, 0);
  Bernstein out(m, 0.0);
  if (n == 0) return out;
  const int si = strides_of<D>(n_)[dir], so = strides_of<D>(m)[dir];
  const double* c = c_.data();
  double* d = out.c_.data();
  for_each_line<D>(n_, m, dir, [&](int a, int b) {
    for (int i = 0; i < n; ++i) d[b + i * so] = n * (c[a + (i + 1) * si] - c[a + i * si]);
  });
  return out;
}

template <int D>
std::pair<Bernstein<D>, Bernstein<D>> Bernstein<D>::subdivide(int dir, double t) const {
  const int n = n_[dir];
  Bernstein left(n_, 0.0), right(n_, 0.0);
  const int s = strides_of<D>(n_)[dir];
  std::vector<double> tmp(n + 1);
  const double t1 = 1.0 - t;
  for_each_line<D>(n_, n_, dir, [&](int a, int) {
    for (int i = 0; i <= n; ++i) tmp[i] = c_[a + i * s];
    left.c_[a] = tmp[0];
    right.c_[a + n * s] = tmp[n];
    for (int r = 1; r <= n; ++r) {
      for (int i = 0; i <= n - r; ++i) tmp[i] = t1 * tmp[i] + t * tmp[i + 1];
      left.c_[a + r * s] = tmp[0];
      right.c_[a + (n - r) * s] = tmp[n - r];
    }
  });
  return {std::move(left), std::move(right)};
}

template <int D>
double Bernstein<D>::variation(int dir) const {
  const int n = n_[dir];
  const int s = strides_of<D>(n_)[dir];
  double v = 0;
  for_each_line<D>(n_, n_, dir, [&](int a, int) {
    for (int i = 0; i < n; ++i) v = std::max(v, std::abs(c_[a + (i + 1) * s] - c_[a + i * s]));
  });
  return v;
}

template <int D>
Bernstein<D>& Bernstein<D>::operator*=(double s) {
  for (double& x : c_) x *= s;
  return *this;
}

template <int D>
Bernstein<D> operator*(const Bernstein<D>& a_in, const Bernstein<D>& b_in) {
  // Scaled coefficients c_i C(n,i) multiply as plain polynomial coefficients (a discrete convolution);
  // dividing by C(n+m, k) returns to the Bernstein basis. The factor with the longer first-direction rows
  // runs in the innermost, contiguous loop.
  const bool swap = a_in.degree(0) > b_in.degree(0);
  const Bernstein<D>& a = swap ? b_in : a_in;
  const Bernstein<D>& b = swap ? a_in : b_in;
  Ints<D> p{};
  for (int k = 0; k < D; ++k) p[k] = a.degree(k) + b.degree(k);
  const Ints<D> sp = strides_of<D>(p);
  std::array<std::vector<double>, D> ba, bb, bp;
  for (int k = 0; k < D; ++k) {
    ba[k] = binomial_row(a.degree(k));
    bb[k] = binomial_row(b.degree(k));
    bp[k] = binomial_row(p[k]);
  }
  // Scaled coefficients of f, and the offset in the product of each coefficient (every_coef = false: of each
  // first-direction row).
  auto scaled = [&](const Bernstein<D>& f, const std::array<std::vector<double>, D>& bin, std::vector<double>& v,
                    std::vector<int>& off, bool every_coef) {
    v.resize(f.size());
    off.clear();
    const auto c = f.coefs();
    for_each_index<D>(f.degrees(), [&](int q, const Ints<D>& i) {
      double w = c[q];
      int o = 0;
      for (int k = 0; k < D; ++k) {
        w *= bin[k][i[k]];
        o += i[k] * sp[k];
      }
      v[q] = w;
      if (every_coef || i[0] == 0) off.push_back(o);
    });
  };
  std::vector<double> va, vb;
  std::vector<int> oa, ob;
  scaled(a, ba, va, oa, true);
  scaled(b, bb, vb, ob, false);
  Bernstein<D> out(p, 0.0);
  double* c = out.coefs().data();
  const int na = a.size(), rows = static_cast<int>(ob.size()), len = b.degree(0) + 1;
  for (int i = 0; i < na; ++i) {
    const double x = va[i];
    for (int r = 0; r < rows; ++r) {
      double* ci = c + oa[i] + ob[r];
      const double* bj = vb.data() + static_cast<std::ptrdiff_t>(r) * len;
      for (int j = 0; j < len; ++j) ci[j] += x * bj[j];
    }
  }
  for_each_index<D>(p, [&](int q, const Ints<D>& i) {
    double d = 1.0;
    for (int k = 0; k < D; ++k) d *= bp[k][i[k]];
    c[q] /= d;
  });
  return out;
}

namespace {

template <int D>
Bernstein<D> combine(const Bernstein<D>& a, const Bernstein<D>& b, double sign) {
  Ints<D> m{};
  for (int k = 0; k < D; ++k) m[k] = std::max(a.degree(k), b.degree(k));
  Bernstein<D> out = a.elevate(m);
  const Bernstein<D> be = b.elevate(m);
  auto oc = out.coefs();
  const auto bc = be.coefs();
  for (std::size_t q = 0; q < oc.size(); ++q) oc[q] += sign * bc[q];
  return out;
}

}  // namespace

template <int D>
Bernstein<D> operator+(const Bernstein<D>& a, const Bernstein<D>& b) {
  return combine(a, b, 1.0);
}

template <int D>
Bernstein<D> operator-(const Bernstein<D>& a, const Bernstein<D>& b) {
  return combine(a, b, -1.0);
}

#define TRIVAR_INSTANTIATE(D)                                                        \
  template class Bernstein<D>;                                                       \
  template Bernstein<D> operator*(const Bernstein<D>&, const Bernstein<D>&);         \
  template Bernstein<D> operator+(const Bernstein<D>&, const Bernstein<D>&);         \
  template Bernstein<D> operator-(const Bernstein<D>&, const Bernstein<D>&);
TRIVAR_INSTANTIATE(1)
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

}  // namespace trivar
