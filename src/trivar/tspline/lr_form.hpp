#pragma once
// A T-spline as an LR spline: its blending functions with gamma 1 over the mesh of their knot lines. The LR
// construction checks that they sum to one on every element, which holds exactly for the T-splines that are
// LR splines (analysis-suitable ones among them); others are refused with the construction's reason.
#include <optional>
#include <string>

#include "trivar/lr/lr_spline.hpp"
#include "trivar/tspline/t_spline_surface.hpp"

namespace trivar {

// Rational (weights kept, homogeneous coefficients) when a weight is not 1. Empty with the reason in `why` when
// the blending functions are no LR spline.
std::optional<LRSpline<2>> lr_form(const TSplineSurface& surface, std::string& why);

}  // namespace trivar
