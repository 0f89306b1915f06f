#pragma once
// The pieces of a volume (parametric dimension 3, up to 3 Cartesian coordinates, rational or not) as trivariate
// polynomials in power form, one per element, in the local coordinates x_k = (u_k - t_s) / (t_{s+1} - t_s) in
// [0, 1] of the element's spans (KnotVector::span_power_form).
//
// For callers that evaluate one volume many times at nearby points (the slicer's chord steps along a row of
// pixels): a point costs Horner's rule on (p+1)^3 coefficient vectors (a tricubic: 48 fused multiply-adds of
// 4-wide vectors along the 16 rows and 15 in the outer directions), with no basis functions, row weights or row
// offsets: 2 to 5 times fewer instructions than the B-spline kernels (AVX2, span search included: 287 against
// 535 at degree 4 x 4 x 4, 70 against 334 at 4 x 4 x 1), for 4 (p+1)^3 doubles per element. The coefficients are
// contracted once per element from the control values and the spans' B-spline power forms. Values agree with
// TensorSpline::eval to about 1e-12 of the control values' magnitude at degree 4 (the power form's coefficients
// exceed the control values by the binomial factors of the basis change), not bit for bit: for iterations whose
// tolerance is far above that (point inversion to 1e-9 of a cell's size), not for results that must equal eval().
//
// Spline degrees 1 to 4 in every direction. The evaluated degrees (after the exact reduction of degrees()) take
// kernels for a second degree equal to the first or 1 (equal degrees; the 4 x 4 x 1, 2 x 2 x 1, 2 x 1 x 1 and
// 2 x 1 x 2 cells of exact spheres, cylinders and tori), other pairs the larger of the two in both (zero
// coefficients). Other degrees, dimensions above 3 and tables over the size cap are not available(), and
// callers keep TensorSpline::eval.
#include <array>
#include <cstddef>
#include <vector>

#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

class ElementPolynomials {
public:
  // Default cap on the table: beyond it the B-spline kernels (which need no table) are the better trade.
  static constexpr std::size_t kDefaultMaxBytes = std::size_t{64} << 20;

  ElementPolynomials() = default;
  // Contracts every element of s; not available() (and empty) when s is outside the supported degrees or
  // dimensions, or the table would exceed max_bytes.
  explicit ElementPolynomials(const TensorSpline<3>& s, std::size_t max_bytes = kDefaultMaxBytes);

  bool available() const { return value_ != nullptr; }
  // The degrees the polynomials have (at most the spline's): a power whose coefficients vanish in every element
  // (to their rounding) is dropped, so a trilinear map stored at degree 4 is evaluated as trilinear.
  const std::array<int, 3>& degrees() const { return degrees_; }
  // The dim Cartesian values at u, clamped to the domain like TensorSpline::eval. Requires available().
  void eval(const Param<3>& u, double* out) const { value_(*this, u, out); }
  // The value and the first partial derivatives in u, v, w, (1 + 3) * dim values in the order of
  // TensorSpline::eval_derivs(u, 1, out). Requires available().
  void eval_first(const Param<3>& u, double* out) const { first_(*this, u, out); }

  // A point kernel (per degree pair and instruction set).
  using Kernel = void (*)(const ElementPolynomials& e, const Param<3>& u, double* out);

private:
  // Per direction: domain, 1 / span length on uniform knots (else 0), last span index (first_span() is 0),
  // offset of the spans' (first knot, 1 / length) pairs in local_, distance between elements in coefs_.
  struct Axis {
    double lo, hi, inv_h, last;
    std::size_t local, step;
  };
  // The span index (from first_span()) of u in direction k on non-uniform knots.
  int search(int k, double u) const { return knots_[k].find_span(u) - knots_[k].first_span(); }

  std::array<Axis, 3> axes_{};
  std::vector<double> local_;
  std::array<KnotVector, 3> knots_{};
  int dim_ = 0;
  std::array<int, 3> degrees_{};
  // Elements with direction 0 fastest; in an element's block the powers of x0 fastest, then x1, x2, each entry 4
  // lanes: the dim coordinates (homogeneous when rational), zeros, and in the last lane the weight (the
  // constant 1 for a polynomial spline, so that one path divides by it exactly).
  std::vector<double> coefs_;
  Kernel value_ = nullptr, first_ = nullptr;

  template <int P0, int P1>
  friend struct ElementKernel;
};

}  // namespace trivar
