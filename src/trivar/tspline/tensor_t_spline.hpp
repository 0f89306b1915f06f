#pragma once
// The T-spline of a tensor-product surface: the T-image is the grid of distinct knots, one T-node per tensor
// B-spline (anchored at its centre knot or centre interval per direction; end knots repeated through the
// T-connect), so the T-spline equals the tensor spline (the blending functions are the tensor B-splines).
#include "trivar/spline/tensor_spline.hpp"
#include "trivar/tspline/t_spline.hpp"

namespace trivar {

// Requires open knot vectors (end multiplicity p + 1) with simple interior knots (a T-image draws each knot
// line once, so a repeated interior knot has no T-spline form here) and dim 1..3 (missing coordinates are 0);
// throws trivar::Error otherwise.
TSpline t_spline_from_tensor(const TensorSpline<2>& s);

}  // namespace trivar
