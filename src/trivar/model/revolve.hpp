#pragma once
// Surfaces and volumes of revolution as exact rational tensor-product splines.
#include <Eigen/Core>

#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

// Sweeps `profile` (a curve for D = 2, a surface for D = 3; control dimension 3) about the axis through
// axis_point with direction axis_dir (any non-zero length) by angle_radians in (0, 2 pi], counter-clockwise
// seen from the tip of axis_dir. The result keeps the profile's directions first and adds the angular
// direction last, on [0, 1]: degree 2, one rational segment per started 90 degrees (a full turn has 4
// segments, 9 control points, knots {0,0,0,1,1,2,2,3,3,4,4,4}/4), middle weights cos(segment / 2) multiplied
// into the profile's weights. The representation is exact: every profile point moves on a circular arc.
// A profile that touches or crosses the axis is accepted, but the result is singular there (det J = 0 on
// the axis, and of changing sign where the profile crosses it). Orientation: det J > 0 where the profile's
// normal (S_u x S_v for a surface profile) points in the direction of rotation; make_rectangle_profile() is
// parametrised that way. Throws trivar::Error on a profile of
// dimension other than 3, a zero axis direction or an angle outside (0, 2 pi].
template <int D>
TensorSpline<D> revolve(const TensorSpline<D - 1>& profile, const Eigen::Vector3d& axis_point,
                        const Eigen::Vector3d& axis_dir, double angle_radians);

}  // namespace trivar
