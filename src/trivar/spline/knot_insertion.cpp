#include "trivar/spline/knot_insertion.hpp"

#include <vector>

#include "trivar/core/error.hpp"
#include "trivar/spline/tensor_map.hpp"

namespace trivar {

template <int D>
TensorSpline<D> insert_knots(const TensorSpline<D>& s, int dir, std::span<const double> knots) {
  require(dir >= 0 && dir < D, "knot insertion: direction " + std::to_string(dir) + " out of range");
  if (knots.empty()) return s;
  KnotVector to = with_knots(s.knots(dir), knots);
  const SparseRowMatrix R = refinement_matrix(s.knots(dir), to);
  return apply_along(s, dir, std::move(to), R);
}

template <int D>
TensorSpline<D> insert_knot(const TensorSpline<D>& s, int dir, double u, int times) {
  require(times >= 0, "knot insertion: negative insertion count " + std::to_string(times));
  const std::vector<double> knots(times, u);
  return insert_knots(s, dir, knots);
}

std::vector<double> uniform_refinement_knots(const KnotVector& kv, int n) {
  require(n >= 1, "refinement: parts per element must be >= 1, got " + std::to_string(n));
  const std::vector<double> bp = kv.breakpoints();
  std::vector<double> z;
  for (std::size_t e = 0; e + 1 < bp.size(); ++e)
    for (int j = 1; j < n; ++j) z.push_back(bp[e] + (bp[e + 1] - bp[e]) * j / n);
  return z;
}

template <int D>
TensorSpline<D> refine_uniform(const TensorSpline<D>& s, const Ints<D>& n) {
  TensorSpline<D> r = s;
  for (int k = 0; k < D; ++k) r = insert_knots(r, k, uniform_refinement_knots(s.knots(k), n[k]));
  return r;
}

#define TRIVAR_INSTANTIATE(D)                                                                   \
  template TensorSpline<D> insert_knots(const TensorSpline<D>&, int, std::span<const double>); \
  template TensorSpline<D> insert_knot(const TensorSpline<D>&, int, double, int);              \
  template TensorSpline<D> refine_uniform(const TensorSpline<D>&, const Ints<D>&);
TRIVAR_INSTANTIATE(1)
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

}  // namespace trivar
