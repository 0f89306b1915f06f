#pragma once
// Reparametrizations that leave the geometry unchanged: reversing a direction, permuting two directions and
// mapping a direction's domain affinely onto another interval.
#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

// r(.., t, ..) = s(.., start + end - t, ..) in direction dir: knots mirrored, control grid reversed.
template <int D>
TensorSpline<D> reverse(const TensorSpline<D>& s, int dir);

// r with directions a and b exchanged: r(.., u_a, .., u_b, ..) = s(.., u_b, .., u_a, ..).
template <int D>
TensorSpline<D> swap_directions(const TensorSpline<D>& s, int a, int b);

// The knots of direction dir mapped affinely so that the domain becomes [a, b] (a < b); r(phi(t)) = s(t).
template <int D>
TensorSpline<D> reparametrize(const TensorSpline<D>& s, int dir, double a, double b);

}  // namespace trivar
