#pragma once
// Lofting: the spline surface through a sequence of curves, or the spline volume through a sequence of
// surfaces, interpolating in the new (last) direction.
#include <vector>

#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

// The spline of degree `degree` in the last direction (domain [0, 1]) with result(.., params[j]) =
// sections[j] for every j. The sections are first made compatible (make_compatible: the result lives on
// sections[0]'s domain in the other directions); then every column of homogeneous coefficients is
// interpolated at `params` with knots by averaging (Piegl & Tiller eq. 9.8), so rational sections are
// reproduced exactly too. Requires at least 2 sections, 1 <= degree < sections.size(), params strictly
// increasing from 0 to 1 (one per section). Throws trivar::Error otherwise, or when interpolated weights
// come out non-positive. D = 2 or 3.
template <int D>
TensorSpline<D> loft(const std::vector<TensorSpline<D - 1>>& sections, const std::vector<double>& params,
                     int degree);

// As above at chord-length parameters: the distance between consecutive sections is the mean distance of
// corresponding control points after make_compatible (a cheap, parametrisation-independent proxy of the
// distance between the sections). Throws trivar::Error when two consecutive sections coincide.
template <int D>
TensorSpline<D> loft(const std::vector<TensorSpline<D - 1>>& sections, int degree);

}  // namespace trivar
