#pragma once
// Extrusion of curves into surfaces and of surfaces into volumes, along a vector or along a path curve.
#include <Eigen/Core>

#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

// base(u) + w direction for w in [0, 1], added as the last direction (degree 1, one element); exact for
// rational bases (the translation acts on homogeneous coefficients as w x -> w x + w d). D = 2 or 3. Throws
// trivar::Error unless direction has base.dim() finite entries.
template <int D>
TensorSpline<D> extrude(const TensorSpline<D - 1>& base, const Eigen::VectorXd& direction);

// base(u) + path(w) - path(w0), w0 = start of the path's domain, with the path's knots as the last
// direction: the base slides along the path without turning, starting where it is. Exact for rational base
// and path: the tensor weights are products w_i v_k and the control points P_i + Q_k - path(w0), which makes
// the rational sum separate. D = 2 or 3. Throws trivar::Error when the control dimensions differ.
template <int D>
TensorSpline<D> extrude_along(const TensorSpline<D - 1>& base, const TensorSpline<1>& path);

}  // namespace trivar
