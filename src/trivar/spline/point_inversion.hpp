#pragma once
// Point inversion: the parameter u with s(u) = x for a spline whose control dimension equals its parametric
// dimension (curves on a line, planar surfaces, volumes in 3-space).
//
// Newton's method solves J du = x - s(u) with steps clamped to the domain and halved until the residual
// decreases, so it cannot diverge; it fails (converged = false) when it stalls, typically because the root
// lies outside the domain. The robust search uses the convex hull property of the Bezier elements (positive
// weights): an element whose control-point bounding box does not contain x cannot contain a preimage. Candidate
// elements are halved by de Casteljau (homogeneous) in the direction of their longest control polygon until
// Newton from a sub-element centre converges or the sub-element is below tolerance; when every candidate has
// been excluded, x is provably not in the image of the domain.
#include <vector>

#include "trivar/core/box.hpp"
#include "trivar/spline/bezier_extraction.hpp"
#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

struct InversionOptions {
  // Model-space residual |s(u) - x| accepted as a solution, relative to the control bounding-box diagonal;
  // also the slack of the bounding-box tests.
  double tolerance = 1e-10;
  // Newton iterations per start.
  int max_newton = 30;
  // Maximum number of halvings of a Bezier element in the robust search.
  int max_depth = 40;
};

template <int D>
struct InversionResult {
  Param<D> param{};
  // found: x lies (within tolerance) in the image of the domain; false only when the search excluded it.
  bool found = false;
  // converged: residual <= tolerance at param.
  bool converged = false;
  // Absolute model-space residual |s(param) - x| (0 when not found).
  double residual = 0;
  // Newton iterations summed over all starts.
  int newton_iterations = 0;
  // The subdivision search ran (no guess, or Newton from the guess failed).
  bool used_fallback = false;
};

// Precomputes the Bezier elements and their bounding boxes once; all queries are const and thread-safe.
template <int D>
class PointInverter {
public:
  // Throws trivar::Error when s.dim() != D or an option is out of range.
  explicit PointInverter(const TensorSpline<D>& s, InversionOptions opts = {});

  // Newton from the guess only: cheap, for tracing along a path of nearby points.
  InversionResult<D> newton(const double* x, const Param<D>& guess) const;
  // Robust search by subdivision of the candidate Bezier elements.
  InversionResult<D> invert(const double* x) const;
  // Newton from the guess, the robust search when that fails.
  InversionResult<D> invert(const double* x, const Param<D>& guess) const;

  const TensorSpline<D>& spline() const { return s_; }
  const InversionOptions& options() const { return opts_; }
  // The absolute model-space tolerance: options().tolerance times the control bounding-box diagonal.
  double absolute_tolerance() const { return tol_; }

private:
  TensorSpline<D> s_;
  InversionOptions opts_;
  std::vector<BezierElement<D>> elements_;
  std::vector<Box<D>> bounds_;  // model-space box of each element's control points
  Box<D> bounds_all_;
  double tol_ = 0;
  int net_size_ = 0;  // doubles per Bezier net
};

extern template class PointInverter<1>;
extern template class PointInverter<2>;
extern template class PointInverter<3>;

// One-shot convenience: builds a PointInverter and runs the robust search.
template <int D>
InversionResult<D> invert(const TensorSpline<D>& s, const double* x, const InversionOptions& opts = {});

}  // namespace trivar
