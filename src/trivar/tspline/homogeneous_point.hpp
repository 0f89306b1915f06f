#pragma once
// A rational control point in homogeneous coordinates (w x, w y, w z, w), where the linear rules of end
// conditions and ghost layers act on weighted points.
#include <array>

#include "trivar/tspline/t_pointset.hpp"

namespace trivar {

using HomogeneousPoint = std::array<double, 4>;

inline HomogeneousPoint homogeneous(const RationalPoint& p) { return {p.w * p.xyz[0], p.w * p.xyz[1], p.w * p.xyz[2], p.w}; }

inline RationalPoint rational(const HomogeneousPoint& h) { return {{h[0] / h[3], h[1] / h[3], h[2] / h[3]}, h[3]}; }

}  // namespace trivar
