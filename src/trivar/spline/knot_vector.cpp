#include "trivar/spline/knot_vector.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "trivar/core/error.hpp"
#include "trivar/core/number_format.hpp"
#include "trivar/core/tolerance.hpp"
#include "trivar/spline/basis.hpp"

namespace trivar {

namespace {

// The power-form block of span s (layout in knot_vector.hpp): the triangular scheme of basis.hpp run on
// polynomials of x, with u - t_k = (t_s - t_k) + h x and t_k - u = (t_k - t_s) - h x, so the coefficients come
// from the knots without sampling or solving.
void append_power_form(const std::vector<double>& t, int p, int s, std::vector<double>& out) {
  constexpr int kW = KnotVector::kMaxPowerFormDegree + 1;
  const double h = t[s + 1] - t[s];
  double N[kW][kW] = {};  // N[r][m]: coefficient of x^m
  N[0][0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    double saved[kW] = {};
    for (int r = 0; r < j; ++r) {
      const double inv = 1.0 / (t[s + 1 + r] - t[s + 1 - j + r]);
      const double right0 = t[s + 1 + r] - t[s], left0 = t[s] - t[s + 1 - j + r];
      double next[kW] = {}, left[kW] = {};
      for (int m = 0; m < j; ++m) {
        const double tmp = N[r][m] * inv;
        next[m] += right0 * tmp;
        next[m + 1] -= h * tmp;
        left[m] += left0 * tmp;
        left[m + 1] += h * tmp;
      }
      for (int m = 0; m <= j; ++m) {
        N[r][m] = saved[m] + next[m];
        saved[m] = left[m];
      }
    }
    for (int m = 0; m <= j; ++m) N[j][m] = saved[m];
  }
  out.push_back(t[s]);
  out.push_back(1.0 / h);
  for (int m = 0; m <= p; ++m)
    for (int a = 0; a <= p; ++a) out.push_back(N[a][m]);
  for (int m = 0; m < p; ++m)
    for (int a = 0; a <= p; ++a) out.push_back((m + 1) * N[a][m + 1] / h);
}

}  // namespace

KnotVector::KnotVector(int degree, std::vector<double> knots) : p_(degree), t_(std::move(knots)) {
  require(p_ >= 0 && p_ <= kMaxDegree, "knot vector: degree " + std::to_string(p_) + " is outside [0, " +
                                           std::to_string(kMaxDegree) + "]");
  const int m = static_cast<int>(t_.size());
  require(m >= 2 * (p_ + 1), "knot vector: degree " + std::to_string(p_) + " needs at least " +
                                 std::to_string(2 * (p_ + 1)) + " knots, got " + std::to_string(m));
  for (int i = 0; i < m; ++i) {
    // Messages are built only on failure: these checks run once per knot.
    require(std::isfinite(t_[i]), [&] { return "knot vector: knot " + std::to_string(i) + " is not finite"; });
    if (i > 0)
      require(t_[i] >= t_[i - 1], [&] {
        return "knot vector: knot " + std::to_string(i) + " (" + format_number(t_[i]) + ") is smaller than knot " +
               std::to_string(i - 1) + " (" + format_number(t_[i - 1]) + "); knots must be non-decreasing";
      });
  }
  for (int i = 0; i < m;) {
    int j = i;
    while (j < m && t_[j] == t_[i]) ++j;
    require(j - i <= p_ + 1, [&] {
      return "knot vector: knot " + format_number(t_[i]) + " at index " + std::to_string(i) + " has multiplicity " +
             std::to_string(j - i) + " > degree + 1 = " + std::to_string(p_ + 1);
    });
    i = j;
  }
  const int n = size();
  require(t_[p_] < t_[n], "knot vector: empty domain [t_" + std::to_string(p_) + ", t_" + std::to_string(n) +
                              "] = [" + format_number(t_[p_]) + ", " + format_number(t_[n]) + "]");
  // Basis evaluation divides by knot differences and find_span by the span length: every difference must be
  // a finite, normal double, and a span below the knot tolerance is a knot written twice with noise.
  require(std::isfinite(t_.back() - t_.front()), [&] {
    return "knot vector: the knots span [" + format_number(t_.front()) + ", " + format_number(t_.back()) +
           "], whose length overflows a double";
  });
  const double min_span = std::max(tol::knot * (t_[n] - t_[p_]), std::numeric_limits<double>::min());
  for (int i = 0; i + 1 < m; ++i)
    require(t_[i + 1] == t_[i] || t_[i + 1] - t_[i] >= min_span, [&] {
      return "knot vector: span [t_" + std::to_string(i) + ", t_" + std::to_string(i + 1) + "] = [" +
             format_number(t_[i]) + ", " + format_number(t_[i + 1]) + "] is non-zero but shorter than " +
             format_number(min_span) + " (" + format_number(tol::knot) + " of the domain length)";
    });
  first_span_ = p_;
  while (t_[first_span_] == t_[first_span_ + 1]) ++first_span_;
  last_span_ = n - 1;
  while (t_[last_span_] == t_[last_span_ + 1]) --last_span_;
  const double h = t_[first_span_ + 1] - t_[first_span_];
  bool uniform = true;
  for (int i = first_span_; i <= last_span_ && uniform; ++i)
    uniform = t_[i + 1] > t_[i] && std::abs((t_[i + 1] - t_[i]) - h) <= 1e-14 * (std::abs(t_[i]) + h);
  if (uniform) uniform_inv_h_ = 1.0 / h;
  // Every difference is positive on a non-empty span: t_{s+1+r} >= t_{s+1} > t_s >= t_{s+1-j+r}.
  for (int sp = first_span_; sp <= last_span_; ++sp)
    for (int j = 1; j <= p_; ++j)
      for (int r = 0; r < j; ++r)
        inv_diff_.push_back(t_[sp] < t_[sp + 1] ? 1.0 / (t_[sp + 1 + r] - t_[sp + 1 - j + r]) : 0.0);
  if (p_ >= 1 && p_ <= kMaxPowerFormDegree) {
    power_form_.reserve(static_cast<std::size_t>(last_span_ - first_span_ + 1) * power_form_block(p_) + 8);
    for (int sp = first_span_; sp <= last_span_; ++sp) {
      if (t_[sp] < t_[sp + 1]) append_power_form(t_, p_, sp, power_form_);
      else power_form_.resize(power_form_.size() + power_form_block(p_), 0.0);
    }
    power_form_.resize(power_form_.size() + 8, 0.0);  // the kernels' vector loads past the last row
  }
}

KnotVector KnotVector::open_uniform(int degree, int elements, double a, double b) {
  require(elements >= 1, "knot vector: number of elements must be >= 1, got " + std::to_string(elements));
  require(a < b, "knot vector: domain [" + format_number(a) + ", " + format_number(b) + "] is empty");
  std::vector<double> bp(elements + 1);
  for (int i = 0; i <= elements; ++i) bp[i] = i == elements ? b : a + (b - a) * i / elements;
  return from_breakpoints(degree, bp);
}

KnotVector KnotVector::from_breakpoints(int degree, std::span<const double> bp, int interior_mult) {
  require(bp.size() >= 2, "knot vector: need at least two breakpoints");
  std::vector<double> t;
  for (size_t i = 0; i < bp.size(); ++i) {
    const int mult = (i == 0 || i + 1 == bp.size()) ? degree + 1 : interior_mult;
    t.insert(t.end(), mult, bp[i]);
  }
  return KnotVector(degree, std::move(t));
}

int KnotVector::multiplicity(double u) const {
  auto r = std::equal_range(t_.begin(), t_.end(), u);
  return static_cast<int>(r.second - r.first);
}

std::vector<double> KnotVector::unique() const {
  std::vector<double> u(t_);
  u.erase(std::unique(u.begin(), u.end()), u.end());
  return u;
}

std::vector<int> KnotVector::multiplicities() const {
  std::vector<int> m;
  for (size_t i = 0; i < t_.size();) {
    size_t j = i;
    while (j < t_.size() && t_[j] == t_[i]) ++j;
    m.push_back(static_cast<int>(j - i));
    i = j;
  }
  return m;
}

std::vector<double> KnotVector::breakpoints() const {
  std::vector<double> b(t_.begin() + p_, t_.begin() + size() + 1);
  b.erase(std::unique(b.begin(), b.end()), b.end());
  return b;
}

std::vector<double> KnotVector::greville() const {
  const int n = size();
  std::vector<double> g(n);
  for (int i = 0; i < n; ++i) {
    if (p_ == 0) {
      g[i] = 0.5 * (t_[i] + t_[i + 1]);
      continue;
    }
    double s = 0;
    for (int j = 1; j <= p_; ++j) s += t_[i + j];
    g[i] = s / p_;
  }
  return g;
}

bool KnotVector::is_clamped() const {
  return multiplicity(t_.front()) == p_ + 1 && multiplicity(t_.back()) == p_ + 1;
}

}  // namespace trivar
