#pragma once
// Axis-aligned blocks with the identity parametrisation: the simplest valid models, used as test inputs
// and by `trivar make box`.
#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

// The block [0, size_0] x ... x [0, size_{D-1}] as a polynomial spline on [0, 1]^D with open uniform knots
// (degrees[k] >= 1, elements[k] >= 1) and control points at the Greville abscissae times size, so the map is
// exactly x_k = size_k * u_k. The control dimension is always 3: a curve lies on the x-axis and a surface in
// the plane z = 0, so every block lives in model space. Throws trivar::Error on a degree or element count
// below 1 or a size that is not positive and finite.
template <int D>
TensorSpline<D> make_block(const Ints<D>& degrees, const Ints<D>& elements, const Param<D>& size);

// Profile for a volume of revolution about the z-axis: the rectangle z in [z0, z1], radius in [r0, r1] in the
// xz-plane, S(u, v) = (r0 + v (r1 - r0), 0, z0 + u (z1 - z0)) on [0, 1]^2: u along the axis, v radial, with the
// given degrees and element counts (u first). In this order (z, r, angle) is a right-handed frame, so revolving
// counter-clockwise about +z gives det J > 0. Throws trivar::Error unless z0 < z1 and r0 < r1 (finite); r0 may
// be zero or negative (the revolved volume is then singular on the axis, see revolve()).
TensorSpline<2> make_rectangle_profile(const Param<2>& heights, const Param<2>& radii, const Ints<2>& degrees = {1, 1},
                                       const Ints<2>& elements = {1, 1});

}  // namespace trivar
