#pragma once
// Applying a 1-D linear map of spline spaces along one direction of a tensor-product spline. Knot insertion,
// degree elevation, reversal and Bezier extraction are all such maps: new coefficients c'(.., k, ..) =
// sum_i R(k, i) c(.., i, ..), applied to homogeneous coefficients so rational splines need no special case.
#include "trivar/spline/knot_refinement.hpp"
#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

// R must be (new_knots.size() x s.count(dir)).
template <int D>
TensorSpline<D> apply_along(const TensorSpline<D>& s, int dir, KnotVector new_knots, const SparseRowMatrix& R);

}  // namespace trivar
