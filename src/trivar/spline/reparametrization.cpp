#include "trivar/spline/reparametrization.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "trivar/core/error.hpp"

namespace trivar {

namespace {

// Knot vector with every knot mapped by the monotone map f whose domain image is [a, b]. The domain ends are
// pinned to a and b exactly and the rest clamped to the correct side of them, so rounding can neither move the
// domain nor break the ordering.
template <class F>
KnotVector map_knots(const KnotVector& kv, double a, double b, F&& f) {
  std::vector<double> t = kv.knots();
  for (double& x : t) {
    if (x == kv.start()) x = a;
    else if (x == kv.end()) x = b;
    else if (x < kv.start()) x = std::min(f(x), a);
    else if (x > kv.end()) x = std::max(f(x), b);
    else x = std::clamp(f(x), a, b);
  }
  return KnotVector(kv.degree(), std::move(t));
}

}  // namespace

template <int D>
TensorSpline<D> reverse(const TensorSpline<D>& s, int dir) {
  require_direction(dir, D, "reverse");
  const KnotVector& kv = s.knots(dir);
  const double a = kv.start(), b = kv.end();
  // Mirroring t -> a + b - t turns an increasing sequence into a decreasing one; reverse the order afterwards.
  std::vector<double> t = kv.knots();
  for (double& x : t) {
    if (x == a) x = b;
    else if (x == b) x = a;
    else if (x < a) x = std::max(a + b - x, b);
    else if (x > b) x = std::min(a + b - x, a);
    else x = std::clamp(a + b - x, a, b);
  }
  std::reverse(t.begin(), t.end());
  auto knots = s.knot_vectors();
  knots[dir] = KnotVector(kv.degree(), std::move(t));

  std::size_t pre = static_cast<std::size_t>(s.stride()), post = 1;
  for (int k = 0; k < dir; ++k) pre *= s.count(k);
  for (int k = dir + 1; k < D; ++k) post *= s.count(k);
  const std::size_t n = kv.size();
  std::vector<double> c(s.coefs().size());
  const double* src = s.coefs().data();
  for (std::size_t o = 0; o < post; ++o)
    for (std::size_t i = 0; i < n; ++i) {
      const double* from = src + (i + n * o) * pre;
      std::copy(from, from + pre, c.begin() + static_cast<std::ptrdiff_t>(((n - 1 - i) + n * o) * pre));
    }
  return TensorSpline<D>(std::move(knots), s.dim(), s.is_rational(), std::move(c));
}

template <int D>
TensorSpline<D> swap_directions(const TensorSpline<D>& s, int a, int b) {
  require_direction(a, D, "swap directions");
  require_direction(b, D, "swap directions");
  if (a == b) return s;
  auto knots = s.knot_vectors();
  std::swap(knots[a], knots[b]);
  std::vector<double> c(s.coefs().size());
  const std::size_t st = static_cast<std::size_t>(s.stride());
  // Linear index in the swapped grid (u fastest) of the swapped multi-index.
  for (int l = 0; l < s.num_coefs(); ++l) {
    auto i = s.multi_index(l);
    std::swap(i[a], i[b]);
    std::size_t m = 0;
    for (int k = D - 1; k >= 0; --k) m = m * static_cast<std::size_t>(knots[k].size()) + i[k];
    std::copy(s.coef(l), s.coef(l) + st, c.begin() + static_cast<std::ptrdiff_t>(m * st));
  }
  return TensorSpline<D>(std::move(knots), s.dim(), s.is_rational(), std::move(c));
}

template <int D>
TensorSpline<D> reparametrize(const TensorSpline<D>& s, int dir, double a, double b) {
  require_direction(dir, D, "reparametrize");
  require(std::isfinite(a) && std::isfinite(b) && a < b, "reparametrize: target interval [" + std::to_string(a) +
                                                             ", " + std::to_string(b) + "] of direction " +
                                                             std::to_string(dir) + " is empty or not finite");
  const KnotVector& kv = s.knots(dir);
  const double t0 = kv.start(), scale = (b - a) / (kv.end() - kv.start());
  auto knots = s.knot_vectors();
  knots[dir] = map_knots(kv, a, b, [&](double x) { return a + (x - t0) * scale; });
  return TensorSpline<D>(std::move(knots), s.dim(), s.is_rational(), {s.coefs().begin(), s.coefs().end()});
}

#define TRIVAR_INSTANTIATE(D)                                                     \
  template TensorSpline<D> reverse(const TensorSpline<D>&, int);                \
  template TensorSpline<D> swap_directions(const TensorSpline<D>&, int, int);   \
  template TensorSpline<D> reparametrize(const TensorSpline<D>&, int, double, double);
TRIVAR_INSTANTIATE(1)
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

}  // namespace trivar
