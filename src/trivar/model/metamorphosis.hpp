#pragma once
// Metamorphosis: the volume swept in time by a surface morphing from one shape into another.
#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

// V(u, v, t) = S0(u, v) + b(t) (S1(u, v) - S0(u, v)) for t in [0, 1], after make_compatible({s0, s1}) (the
// result lives on s0's domain; s1 is mapped affinely onto it). The time blend b is the smoothstep of order
// `smoothness` (k): the Bezier function of degree 2k + 1 with k + 1 coefficients 0 then k + 1 coefficients 1,
// whose derivatives of orders 1..k vanish at both ends (ease in and out). k = 0 is the linear morph, i.e.
// ruled(s0, s1); k = 1 gives b = 3t^2 - 2t^3, k = 2 gives 10t^3 - 15t^4 + 6t^5. The blend acts on
// homogeneous coefficients, with the same meaning for rational inputs as in ruled(). Throws trivar::Error
// when the control dimensions differ or smoothness is negative.
SplineVolume metamorphosis(const SplineSurface& s0, const SplineSurface& s1, int smoothness = 0);

}  // namespace trivar
