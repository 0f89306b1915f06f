#pragma once
// Length, area and volume of splines by Gauss quadrature per element (exact for polynomial integrands up to
// degree 2n - 1 in each direction; rational maps converge spectrally with n).
#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

// Integral of sqrt(det(J^T J)) over the domain: arc length, surface area or volume (unsigned), for any
// control dimension >= D. n Gauss points per element and direction.
template <int D>
double measure(const TensorSpline<D>& s, int n, int threads = 0);

// Integral of det J for a map with dim() == D: the signed volume (area), negative for a left-handed map.
template <int D>
double signed_measure(const TensorSpline<D>& s, int n, int threads = 0);

}  // namespace trivar
