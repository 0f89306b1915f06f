#pragma once
// Upper bounds on the second derivatives of a Bezier patch, rational or not, over its whole parameter square
// (derivatives with respect to the unit parameters, not the domain's). With x = Y / W (Y the homogeneous
// coordinates, W the weight function; W = 1 when not rational) and Z = W Y_u - W_u Y (x_u = Z / W^2)
//   x_uu = (W Z_u - 2 W_u Z) / W^3,   x_uv = (W Z_v - 2 W_v Z) / W^3,
// and x_vv alike from W Y_v - W_v Y: the numerators and W^3 are polynomials, written exactly in Bernstein form
// (products of Bernstein polynomials), so |numerator| <= its largest coefficient (in the Euclidean norm over the
// components) and W^3 >= its smallest coefficient: both bounds hold everywhere on the patch, and they are tight
// to the extent the Bernstein coefficients are (no sampling).
#include "trivar/spline/bezier_extraction.hpp"

namespace trivar {

struct SecondDerivativeBound {
  double uu = 0, uv = 0, vv = 0;  // >= sup |x_uu|, |x_uv|, |x_vv| over [0, 1]^2
};

// Infinite bounds when a weight coefficient of W^3 is not positive (the rational patch may have a pole).
SecondDerivativeBound second_derivative_bound(const BezierElement<2>& patch);

}  // namespace trivar
