#pragma once
// Exact rational quadratic circular arcs, and the non-singular cell layout of a disk that the cylinder, cone
// and torus primitives are built from.
#include <array>

#include <Eigen/Core>

#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

// center + radius (cos a x_axis + sin a y_axis) for a from start_angle to end_angle (either sense, at most a
// full turn), on [0, 1]: degree 2, one rational segment per started quarter turn (interior knots doubled),
// middle weights cos(segment / 2). Throws trivar::Error unless radius > 0, the axes are orthonormal (to
// 1e-12) and 0 < |end_angle - start_angle| <= 2 pi.
SplineCurve circle_arc(const Eigen::Vector3d& center, const Eigen::Vector3d& x_axis, const Eigen::Vector3d& y_axis,
                       double radius, double start_angle, double end_angle);

// The disk of `radius` about the origin in the plane z = 0 as five rational surfaces with positive
// orientation (S_u x S_v along +z): [0] the square [-s, s]^2 with s = core * radius / sqrt(2), degree (2, 2)
// with unit weights; [1..4] the ruled cells between the square's sides and the quarter arcs centred on the
// +x, +y, -x, -y axes, u along the side (degree 2) and v outward (degree 1). The outer cells are copies of
// the +x cell turned by quarter turns (exact: the rotation only swaps and negates coordinates), so
// neighbours share identical edges. Throws trivar::Error unless radius > 0 and 0 < core < 1.
std::array<SplineSurface, 5> disk_cells(double radius, double core);

}  // namespace trivar
