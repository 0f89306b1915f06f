#pragma once
// The LR benchmark splines of issue 3: the identity map on [0,1]^D as a cubic spline with n open uniform
// elements per direction, refined level by level on every element (FULLSPAN, MINSPAN) or B-spline (STRUCTURED)
// whose open interior meets the diagonal segment (0,..,0)-(1,..,1).
#include <vector>

#include "trivar/lr/refinement.hpp"
#include "trivar/lr/selection.hpp"

namespace trivar::bench {

// Greville control points, so the spline is the identity map.
template <int D>
LRSpline<D> unit_lr(int n) {
  std::array<KnotVector, D> kv;
  for (auto& k : kv) k = KnotVector::open_uniform(3, n);
  const int m = kv[0].size();
  const auto g = kv[0].greville();
  std::vector<double> coef;
  int total = 1;
  for (int k = 0; k < D; ++k) total *= m;
  for (int i = 0; i < total; ++i) {
    int r = i;
    for (int k = 0; k < D; ++k) {
      coef.push_back(g[static_cast<std::size_t>(r % m)]);
      r /= m;
    }
  }
  return LRSpline<D>(TensorSpline<D>(kv, D, false, coef));
}

// One level: selection and refinement; returns the number of elements or B-splines selected.
template <int D>
std::size_t refine_diagonal(LRSpline<D>& lr, Strategy strategy) {
  Param<D> p0{}, p1{};
  p1.fill(1.0);
  const RefineOptions opts{strategy, 1, 0.0};
  if (strategy == Strategy::structured) {
    const auto ids = functions_on_segment(lr, p0, p1);
    refine_functions(lr, std::span<const int>(ids), opts);
    return ids.size();
  }
  const auto ids = elements_on_segment(lr, p0, p1);
  refine_elements(lr, std::span<const int>(ids), opts);
  return ids.size();
}

}  // namespace trivar::bench
