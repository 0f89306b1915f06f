#pragma once
// The graph (u, v, h(u, v)) of a height field as a parametric LR surface: the same mesh and B-splines, control
// points (Greville abscissae, height coefficient). LR B-splines reproduce linear functions with their Greville
// abscissae (the mean of a B-spline's p inner local knots, times the same scaling the partition of unity uses), so
// the graph's x and y are exactly u and v: a fitted terrain becomes geometry for .g2, STEP and VTK viewers.
#include "trivar/lr/lr_spline.hpp"

namespace trivar {

// Throws trivar::Error unless `height` has one component and is polynomial.
LRSpline<2> graph_surface(const LRSpline<2>& height);

}  // namespace trivar
