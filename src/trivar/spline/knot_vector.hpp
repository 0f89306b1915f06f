#pragma once
// KnotVector: a validated, non-decreasing knot sequence of a given degree, with the queries every spline
// algorithm needs (span search, multiplicities, breakpoints, Greville abscissae).
#include <algorithm>
#include <span>
#include <vector>

namespace trivar {

class KnotVector {
public:
  KnotVector() = default;
  // Validates: finite, non-decreasing, >= 2(p+1) knots, multiplicities <= p+1, a non-empty domain, a finite
  // overall length, non-zero spans >= tol::knot x the domain length. Throws trivar::Error naming the knot index.
  KnotVector(int degree, std::vector<double> knots);

  // Clamped (open) knot vector on [a, b] with `elements` equal intervals.
  static KnotVector open_uniform(int degree, int elements, double a = 0.0, double b = 1.0);
  // Clamped knot vector with the given distinct breakpoints, interior ones of multiplicity `interior_mult`.
  static KnotVector from_breakpoints(int degree, std::span<const double> breakpoints, int interior_mult = 1);

  int degree() const { return p_; }
  int order() const { return p_ + 1; }
  // Number of B-splines (control points) in this direction.
  int size() const { return static_cast<int>(t_.size()) - p_ - 1; }
  const std::vector<double>& knots() const { return t_; }
  const double* data() const { return t_.data(); }
  double operator[](int i) const { return t_[i]; }
  double start() const { return t_[p_]; }
  double end() const { return t_[size()]; }

  // Index s with t_s <= u < t_{s+1} and t_s < t_{s+1}, p <= s < n. Parameters left of the domain map to the
  // first span and parameters at or right of the end to the last non-empty span, so u = end() evaluates the
  // closed right end of the domain.
  inline int find_span(double u) const;
  // Number of knots equal to u (exact comparison: knots are data, not results of arithmetic).
  int multiplicity(double u) const;
  // Distinct knot values of the whole vector and their multiplicities.
  std::vector<double> unique() const;
  std::vector<int> multiplicities() const;
  // Distinct knot values inside the domain [start, end]: the element boundaries.
  std::vector<double> breakpoints() const;
  int num_elements() const { return static_cast<int>(breakpoints().size()) - 1; }
  // Greville abscissae (t_{i+1} + ... + t_{i+p}) / p; for p = 0 the interval midpoints.
  std::vector<double> greville() const;
  // True when both ends have multiplicity p+1 (the usual clamped form).
  bool is_clamped() const;

  // Reciprocals of the knot differences t_{s+1+r} - t_{s+1-j+r} (j = 1..p, r = 0..j-1, in that order) that the
  // triangular basis scheme divides by on span s; precomputed so per-point evaluation only multiplies.
  const double* inverse_differences(int span) const {
    return inv_diff_.data() + static_cast<std::size_t>(span - first_span_) * (p_ * (p_ + 1) / 2);
  }

  // The B-splines of span s as polynomials of the local coordinate x = (u - t_s) / (t_{s+1} - t_s) in [0, 1]
  // (degrees 1 to kMaxPowerFormDegree, the degrees of the evaluation kernels; null otherwise): the block holds
  // t_s, 1 / (t_{s+1} - t_s), then the power coefficients C[m][a] of x^m in B_{s-p+a} (m, a = 0..p, a fastest),
  // then D[m][a] = (m + 1) C[m + 1][a] / (t_{s+1} - t_s) (m = 0..p-1), the coefficients of the derivatives with
  // respect to u. The kernels evaluate the basis of a direction by Horner's rule, p fused multiply-adds of
  // vectors over a, instead of the triangular scheme; loads of up to 8 values past any row stay inside the
  // table. On a local coordinate the coefficients stay bounded for any knot spacing (the polynomials are
  // bounded by 1 on [0, 1]), so the values agree with the triangular scheme to a few units in the last place.
  static constexpr int kMaxPowerFormDegree = 4;
  static constexpr int power_form_block(int p) { return 2 + (2 * p + 1) * (p + 1); }
  // The blocks of spans first_span() .. last_span() in order (empty spans have zero blocks).
  const double* power_forms() const { return power_form_.empty() ? nullptr : power_form_.data(); }
  const double* span_power_form(int span) const {
    return power_forms() + static_cast<std::size_t>(span - first_span_) * power_form_block(p_);
  }
  // The first and last non-empty spans, and 1 / (span length) when the spans between them are equal (0
  // otherwise), which lets the kernels find the span of u by one multiplication.
  int first_span() const { return first_span_; }
  int last_span() const { return last_span_; }
  double uniform_inverse_spacing() const { return uniform_inv_h_; }

  bool operator==(const KnotVector& o) const { return p_ == o.p_ && t_ == o.t_; }

private:
  int p_ = 0;
  std::vector<double> t_;
  int first_span_ = 0;
  int last_span_ = 0;
  // Set when the interior knots are simple and equally spaced: find_span is then O(1).
  double uniform_inv_h_ = 0.0;
  std::vector<double> inv_diff_;
  std::vector<double> power_form_;
};

inline int KnotVector::find_span(double u) const {
  if (uniform_inv_h_ > 0.0) {
    // Guess from the spacing (the clamp also handles parameters outside the domain), then correct the
    // rounding of the product by at most one step.
    const double x = (u - t_[first_span_]) * uniform_inv_h_;
    int s = first_span_ + static_cast<int>(std::clamp(x, 0.0, static_cast<double>(last_span_ - first_span_)));
    if (s > first_span_ && u < t_[s]) --s;
    if (s < last_span_ && u >= t_[s + 1]) ++s;
    return s;
  }
  if (u >= t_[last_span_ + 1]) return last_span_;
  if (u < t_[first_span_ + 1]) return first_span_;
  auto it = std::upper_bound(t_.begin() + first_span_ + 1, t_.begin() + last_span_ + 1, u);
  return static_cast<int>(it - t_.begin()) - 1;
}

}  // namespace trivar
