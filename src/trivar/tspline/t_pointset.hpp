#pragma once
// The cartesian layer of a T-spline (Xiao et al. 2016): the T-pointset, rational points (x, y, z, weight),
// one per T-node. Points are stored in cartesian form; the surface is sum w_i P_i B_i / sum w_i B_i.
#include <array>
#include <vector>

namespace trivar {

struct RationalPoint {
  std::array<double, 3> xyz{};
  double w = 1.0;
};

struct TPointset {
  std::vector<RationalPoint> points;
};

}  // namespace trivar
