#pragma once
// A T-spline as one rational tensor Bezier patch per Bezier element (knots p + 1 times at the element's ends,
// homogeneous coefficients (w x, w y, w z, w) from the element's net): the form every spline reader takes
// (GoTools .g2 SplineSurface, IGES 128, STEP B-spline surfaces), exact for any T-spline, also one whose
// blending functions do not sum to one. Neighbouring patches meet exactly on their shared sides (the same
// T-spline evaluated there), as the per-face Bezier export of Rhino's T-splines does.
#include <vector>

#include "trivar/spline/tensor_spline.hpp"
#include "trivar/tspline/t_spline_surface.hpp"

namespace trivar {

std::vector<TensorSpline<2>> bezier_patches(const TSplineSurface& surface);

}  // namespace trivar
