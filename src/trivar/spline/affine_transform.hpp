#pragma once
// Affine maps of the geometry, x -> A x + b. Applied to homogeneous coefficients as (w x, w) -> (A (w x) + w b, w),
// which is exact for rational splines because an affine map commutes with the rational (projective) sum.
#include <Eigen/Core>

#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

// A is (m x s.dim()), b has m entries; the result has control dimension m (m = dim for a motion or scaling,
// m != dim to embed or project). Throws trivar::Error on a size mismatch or non-finite entries.
template <int D>
TensorSpline<D> transform(const TensorSpline<D>& s, const Eigen::MatrixXd& A, const Eigen::VectorXd& b);

}  // namespace trivar
