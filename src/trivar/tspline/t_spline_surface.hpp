#pragma once
// TSplineSurface: a T-spline ready to evaluate. Built once from the three layers: the blending functions
// (local_knots.hpp), the Bezier elements (the cells of the grid of all knot values that lie in a T-face; every
// blending function is one polynomial on each), each element's extraction operator (lr/lr_bezier_extraction)
// and its Bezier net of the homogeneous surface (sum w_i P_i B_i, sum w_i B_i). Evaluation locates the element
// by two binary searches and sums one tensor Bernstein patch: sum w_i P_i B_i / sum w_i B_i, the rational
// form the seed-002 prototype and Rhino use, which is the T-spline also when the blending functions do not sum
// to one (T-meshes that are not analysis-suitable).
#include <span>
#include <vector>

#include "trivar/core/box.hpp"
#include "trivar/lr/lr_bezier_extraction.hpp"
#include "trivar/lr/lr_bspline.hpp"
#include "trivar/spline/bezier_extraction.hpp"
#include "trivar/tspline/t_spline.hpp"

namespace trivar {

// The sum of the (unweighted) blending functions, bounded on every element by the range of its Bernstein
// coefficients (the sum is a polynomial there): it lies in [min_sum, max_sum]; it is 1 everywhere exactly when
// every coefficient is 1 (max_defect = 0 up to rounding).
struct PartitionOfUnity {
  double min_sum = 1, max_sum = 1;
  double max_defect = 0;  // max |coefficient - 1|
  double sampled_min = 1, sampled_max = 1;  // the sum at 5 x 5 points per element (attained values)
  int elements_off = 0;   // elements with a coefficient off 1 by more than 1e-12
};

class TSplineSurface {
public:
  explicit TSplineSurface(const TSpline& ts, int threads = 0);
  // The elements inside `regions` alone (boxes of the domain: the faces wanted of a larger T-spline; each element
  // as the whole surface's); elsewhere as in a hole.
  TSplineSurface(const TSpline& ts, const std::vector<Box<2>>& regions, int threads = 0);
  // From the blending functions alone (as a Part 42 locally refined surface stores a T-spline): each with
  // p_k + 2 local knots, gamma 1 and the homogeneous value (w x, w y, w z, w); the domain is the union of the
  // supports. Throws trivar::Error for a malformed function.
  TSplineSurface(const Ints<2>& degrees, std::vector<LRBSpline<2>> basis, int threads = 0);

  const Ints<2>& degrees() const { return degrees_; }
  const Box<2>& domain() const { return domain_; }
  std::span<const LRBSpline<2>> basis() const { return basis_; }
  std::span<const Box<2>> elements() const { return elements_; }
  const Incidence& element_supports() const { return supports_; }
  const std::vector<BezierElement<2>>& bezier_elements() const { return bezier_; }
  const PartitionOfUnity& partition_of_unity() const { return pu_; }

  // The element containing u (half-open cells, the domain's upper ends closed), -1 outside the T-faces.
  int locate(const Param<2>& u) const;
  // x, y, z at u; NaN when u lies outside the T-faces (a hole or outside the domain).
  void eval(const Param<2>& u, double* out) const;
  // Value, d/ds, d/dt: 9 values.
  void eval_first_derivatives(const Param<2>& u, double* out) const;
  // x, y, z at u by element e's patch (u in its closed box): points on a side shared with a hole or with
  // another element, evaluated by the element that owns them.
  void eval_on_element(int e, const Param<2>& u, double* out) const;
  // Value, d/ds, d/dt by element e's patch (9 values).
  void eval_first_derivatives_on_element(int e, const Param<2>& u, double* out) const;
  // eval at every u (out: 3 per point), threads as parallel_for (<= 0: all).
  void eval_many(std::span<const Param<2>> u, std::span<double> out, int threads = 0) const;

private:
  Ints<2> degrees_{};
  Box<2> domain_{};
  std::vector<LRBSpline<2>> basis_;
  std::array<std::vector<double>, 2> lines_;  // all knot values per direction
  std::vector<int> cell_element_;              // per grid cell, s fastest: element or -1
  std::vector<Box<2>> elements_;
  Incidence supports_;
  std::vector<BezierElement<2>> bezier_;
  PartitionOfUnity pu_;

  // Elements: the cells of the grid of all knot values inside one of the regions.
  void build(const std::vector<Box<2>>& regions, int threads);
  template <bool kDerivatives>
  void eval_impl(const Param<2>& u, double* out) const { eval_element<kDerivatives>(locate(u), u, out); }
  template <bool kDerivatives>
  void eval_element(int e, const Param<2>& u, double* out) const;
};

}  // namespace trivar
