#pragma once
// LRBSpline<D>: one scaled tensor-product B-spline of a locally refined spline: per direction a local knot
// vector of p_k + 2 knots, a scaling factor gamma in (0, 1] and a control value (homogeneous when rational).
// Every locally refined kind (LR, hierarchical, T-splines) is a collection of these over a box mesh.
#include <array>
#include <vector>

#include "trivar/core/box.hpp"

namespace trivar {

template <int D>
struct LRBSpline {
  std::array<std::vector<double>, D> knots;  // p_k + 2 local knots in direction k
  double gamma = 1.0;
  std::vector<double> coef;                  // stride() values, homogeneous when rational

  Box<D> support() const {
    Box<D> b;
    for (int k = 0; k < D; ++k) {
      b.lo[k] = knots[k].front();
      b.hi[k] = knots[k].back();
    }
    return b;
  }
};

}  // namespace trivar
