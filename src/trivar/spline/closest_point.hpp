#pragma once
// Closest point on a spline (a curve or surface in any dimension; also a volume, where points inside have
// distance 0) to a point x: the global minimum of |s(u) - x| over the closed domain.
//
// Branch and bound over the Bezier elements: a node's lower bound is the distance from x to the bounding box of
// its control points in an orthonormal frame aligned with the node's tangents (convex hull property; tight to
// second order for small nodes, unlike an axis-aligned box). Nodes are visited best bound first; a node whose
// centre beats the best distance so far (and every element) starts a bound-constrained Newton minimisation of
// |s(u) - x|^2 / 2 with gradient and Hessian from the second derivatives; variables at a domain bound with the
// gradient pointing outward are held fixed, so minima on boundary edges and corners are found. Nodes are halved
// (de Casteljau, along their longest control polygon) until their bound cannot improve the best distance by more
// than 1e-7 of the model size, so the result is the global minimum up to that gap (ties within it may resolve
// either way) and is Newton-accurate. A node budget bounds the work when a continuum of points is equally close
// (x at the centre of a spherical patch).
#include <vector>

#include "trivar/core/box.hpp"
#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

template <int D>
struct ClosestPoint {
  Param<D> param{};
  std::vector<double> point;  // s(param), dim values
  double distance = 0;        // |s(param) - x|
  // Newton met the first-order optimality conditions: the residual's component along every free tangent is
  // below tolerance times the control bounding-box diagonal.
  bool converged = false;
};

// tolerance: relative to the control bounding-box diagonal (default 1e-12). Throws trivar::Error when the
// tolerance is not positive.
template <int D>
ClosestPoint<D> closest_point(const TensorSpline<D>& s, const double* x, double tolerance = 1e-12);

}  // namespace trivar
