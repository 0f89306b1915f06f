#pragma once
// Memory an LR spline of given counts takes while it is refined, for refusing a request before it exhausts the
// memory (core/memory_budget.hpp). An estimate from the data layout of LRSpline and its refinement, in double
// so that counts of an absurd request cannot overflow.
#include <cstddef>
#include <vector>

#include "trivar/core/box.hpp"
#include "trivar/lr/lr_bspline.hpp"

namespace trivar {

template <int D>
double lr_spline_bytes(const Ints<D>& degrees, int stride, double basis, double elements) {
  double local = 1.0, knots = 0.0;
  for (int k = 0; k < D; ++k) {
    local *= degrees[k] + 1;
    knots += degrees[k] + 2;
  }
  constexpr double kList = sizeof(std::vector<int>);
  // A B-spline: its knots, control value, support list (about (p+1)^D elements) and hash slots. An element: its
  // box, its list of (p+1)^D B-splines and the evaluation data (one entry and Bernstein rows per B-spline).
  const double per_basis = sizeof(LRBSpline<D>) + 8.0 * (knots + stride) + kList + 4.0 * local + 32.0;
  const double per_element = sizeof(Box<D>) + kList + 4.0 * local + 8.0 * local + 8.0 * knots;
  // A refinement holds the old and the new collections at once.
  return 2.0 * (basis * per_basis + elements * per_element);
}

}  // namespace trivar
