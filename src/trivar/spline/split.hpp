#pragma once
// Cutting tensor-product splines into pieces. A cut inserts the knot to full multiplicity p+1, after which the
// control grid separates into independent clamped splines that reproduce the original on their sub-domains.
// The same subdivision on a single Bezier net (de Casteljau) drives point inversion and closest-point search.
#include <utility>

#include "trivar/core/box.hpp"
#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

// The two pieces of s on [start, u] and [u, end] in direction dir. A cut within tol::knot (relative to the
// domain length) of an existing knot snaps to it. Throws trivar::Error for a bad direction or a cut that is
// not strictly inside the domain.
template <int D>
std::pair<TensorSpline<D>, TensorSpline<D>> split_at(const TensorSpline<D>& s, int dir, double u);

// The piece of s over `box` (inside the domain, non-empty in every direction), clamped on all sides.
template <int D>
TensorSpline<D> sub_patch(const TensorSpline<D>& s, const Box<D>& box);

// De Casteljau subdivision of one Bezier net (degrees per direction, u fastest, `stride` values per point,
// homogeneous when rational) at local parameter t in (0, 1) of direction dir. left and right receive nets of
// the same shape as `net`; neither may alias it.
template <int D>
void split_bezier_net(const Ints<D>& degrees, int stride, const double* net, int dir, double t, double* left,
                      double* right);

}  // namespace trivar
