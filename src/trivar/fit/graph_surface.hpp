#pragma once
// The graph (u, v, h(u, v)) of a height field as a parametric LR surface: the same mesh and B-splines, control
// points (x, y, height coefficient), where x and y are the coefficients of the identity map on those B-splines.
// Greville abscissae give them only for a tensor spline: after local refinement a B-spline's identity
// coefficient is whatever the splits combined, so the identity is carried through refinement (exactly, as any
// geometry) from the initial tensor spline. A fitted terrain becomes geometry for .g2, STEP and VTK viewers.
#include "trivar/lr/lr_spline.hpp"

namespace trivar {

// `parameters` holds the identity map (two values per B-spline) on the B-splines of `height`. Throws
// trivar::Error unless `height` has one component and is polynomial and the two have the same B-splines.
LRSpline<2> graph_surface(const LRSpline<2>& height, const LRSpline<2>& parameters);

}  // namespace trivar
