#pragma once
// Iso-parametric sub-entities: fixing one parameter of a surface gives a curve, of a volume a surface. The
// basis in the fixed direction is contracted at u on homogeneous coefficients, so rational splines stay exact.
#include <array>

#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

// The (D-1)-variate spline s(.., u, ..) with u in direction dir; the remaining directions keep their order.
// Throws trivar::Error for a bad direction or u outside the domain. D = 2, 3.
template <int D>
TensorSpline<D - 1> iso_extract(const TensorSpline<D>& s, int dir, double u);

// The 2*D boundary faces: dir 0 at start, dir 0 at end, dir 1 at start, dir 1 at end (, dir 2 start, end).
template <int D>
std::array<TensorSpline<D - 1>, 2 * D> boundary_faces(const TensorSpline<D>& s);

}  // namespace trivar
