#pragma once
// Making several tensor-product splines share one spline space, so that constructions which combine their
// control nets coefficient by coefficient (ruled, lofted and Boolean-sum volumes) become possible. Every step
// keeps the geometry: affine reparametrization, degree elevation and knot insertion are exact.
#include <vector>

#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

// The splines written in a common space, in order:
// - unclamped knot vectors are clamped to their domain;
// - each direction is mapped affinely onto the domain of the first spline in that direction, so output i
//   evaluated at phi(u) equals input i at u (phi = identity where the domains already agree);
// - each direction is raised to the largest degree among the inputs (elevate_degree);
// - every knot value gets the largest multiplicity it has in any input (insert_knots), so all outputs have
//   identical knot vectors. Knots are compared exactly: two knots that differ by rounding stay distinct;
// - if any input is rational all outputs are (polynomial inputs get unit weights).
// Throws trivar::Error when the control dimensions differ. An empty input gives an empty output.
template <int D>
std::vector<TensorSpline<D>> make_compatible(const std::vector<TensorSpline<D>>& splines);

}  // namespace trivar
