#pragma once
// Ruled surfaces (between two curves) and ruled volumes (between two surfaces).
#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

// (1 - w) a + w b for w in [0, 1], added as the last direction (degree 1, one element), after
// make_compatible({a, b}) (so the result lives on a's domain in the other directions, and b is mapped
// affinely onto it). The blend acts on homogeneous coefficients: for polynomial inputs, and for rational ones
// whose weights agree after compatibility (e.g. coaxial arcs), it is exactly (1 - w) a(u) + w b(u); for other
// rational inputs it is the rational ruled surface/volume with the same boundaries a (w = 0) and b (w = 1).
// D = 2 (surface from curves) or 3 (volume from surfaces). Throws trivar::Error when the control dimensions
// differ.
template <int D>
TensorSpline<D> ruled(const TensorSpline<D - 1>& a, const TensorSpline<D - 1>& b);

}  // namespace trivar
