#include "trivar/spline/split.hpp"

#include <algorithm>
#include <string>

#include "trivar/core/error.hpp"
#include "trivar/core/tolerance.hpp"
#include "trivar/spline/basis.hpp"
#include "trivar/spline/knot_insertion.hpp"

namespace trivar {

namespace {

// Cuts are usually computed values; a cut a rounding error away from a knot would create a sliver element.
double snap_to_knot(const KnotVector& kv, double u) {
  const double eps = tol::knot * (kv.end() - kv.start());
  const auto& t = kv.knots();
  const auto it = std::lower_bound(t.begin(), t.end(), u);
  if (it != t.end() && *it - u <= eps) return *it;
  if (it != t.begin() && u - *(it - 1) <= eps) return *(it - 1);
  return u;
}

// The piece of s over [a, b] in direction dir, start <= a < b <= end, both already snapped.
template <int D>
TensorSpline<D> restrict_to(const TensorSpline<D>& s, int dir, double a, double b) {
  const int p = s.degree(dir);
  TensorSpline<D> r = s;
  for (double c : {a, b}) {
    const int m = r.knots(dir).multiplicity(c);
    if (m < p + 1) r = insert_knot(r, dir, c, p + 1 - m);
  }
  const auto& t = r.knots(dir).knots();
  // With a and b of multiplicity p+1, the B-splines first .. last-1 are exactly those non-zero on (a, b).
  const int first = static_cast<int>(std::lower_bound(t.begin(), t.end(), a) - t.begin());
  const int last = static_cast<int>(std::lower_bound(t.begin(), t.end(), b) - t.begin());
  auto knots = r.knot_vectors();
  knots[dir] = KnotVector(p, std::vector<double>(t.begin() + first, t.begin() + last + p + 1));

  std::size_t pre = static_cast<std::size_t>(r.stride()), post = 1;
  for (int k = 0; k < dir; ++k) pre *= r.count(k);
  for (int k = dir + 1; k < D; ++k) post *= r.count(k);
  const std::size_t n_old = r.count(dir), n_new = static_cast<std::size_t>(last - first);
  std::vector<double> c(pre * n_new * post);
  const double* src = r.coefs().data();
  for (std::size_t o = 0; o < post; ++o) {
    const double* from = src + (static_cast<std::size_t>(first) + n_old * o) * pre;
    std::copy(from, from + n_new * pre, c.begin() + static_cast<std::ptrdiff_t>(n_new * o * pre));
  }
  return TensorSpline<D>(std::move(knots), r.dim(), r.is_rational(), std::move(c));
}

}  // namespace

template <int D>
std::pair<TensorSpline<D>, TensorSpline<D>> split_at(const TensorSpline<D>& s, int dir, double u) {
  require_direction(dir, D, "split");
  const KnotVector& kv = s.knots(dir);
  const double c = snap_to_knot(kv, u);
  require(c > kv.start() && c < kv.end(), "split: parameter " + std::to_string(u) + " in direction " +
                                              std::to_string(dir) + " is not inside the domain (" +
                                              std::to_string(kv.start()) + ", " + std::to_string(kv.end()) + ")");
  // Insert once; both halves then find the cut at full multiplicity.
  const int m = kv.multiplicity(c);
  const TensorSpline<D> r = m < kv.order() ? insert_knot(s, dir, c, kv.order() - m) : s;
  return {restrict_to(r, dir, r.knots(dir).start(), c), restrict_to(r, dir, c, r.knots(dir).end())};
}

template <int D>
TensorSpline<D> sub_patch(const TensorSpline<D>& s, const Box<D>& box) {
  TensorSpline<D> r = s;
  for (int k = 0; k < D; ++k) {
    const KnotVector& kv = s.knots(k);
    const double a = snap_to_knot(kv, box.lo[k]), b = snap_to_knot(kv, box.hi[k]);
    require(a >= kv.start() && b <= kv.end() && a < b,
            "sub-patch: interval [" + std::to_string(box.lo[k]) + ", " + std::to_string(box.hi[k]) +
                "] in direction " + std::to_string(k) + " is empty or not inside the domain [" +
                std::to_string(kv.start()) + ", " + std::to_string(kv.end()) + "]");
    r = restrict_to(r, k, a, b);
  }
  return r;
}

template <int D>
void split_bezier_net(const Ints<D>& degrees, int stride, const double* net, int dir, double t, double* left,
                      double* right) {
  std::size_t pre = static_cast<std::size_t>(stride), post = 1;
  for (int k = 0; k < dir; ++k) pre *= static_cast<std::size_t>(degrees[k] + 1);
  for (int k = dir + 1; k < D; ++k) post *= static_cast<std::size_t>(degrees[k] + 1);
  const int p = degrees[dir];
  const std::size_t line = pre * static_cast<std::size_t>(p + 1);
  double tmp[kMaxDegree + 1];
  for (std::size_t o = 0; o < post; ++o)
    for (std::size_t j = 0; j < pre; ++j) {
      const std::size_t base = o * line + j;
      for (int i = 0; i <= p; ++i) tmp[i] = net[base + i * pre];
      left[base] = tmp[0];
      right[base + p * pre] = tmp[p];
      for (int r = 1; r <= p; ++r) {
        for (int i = 0; i + r <= p; ++i) tmp[i] = (1.0 - t) * tmp[i] + t * tmp[i + 1];
        left[base + r * pre] = tmp[0];
        right[base + (p - r) * pre] = tmp[p - r];
      }
    }
}

#define TRIVAR_INSTANTIATE(D)                                                                               \
  template std::pair<TensorSpline<D>, TensorSpline<D>> split_at(const TensorSpline<D>&, int, double);     \
  template TensorSpline<D> sub_patch(const TensorSpline<D>&, const Box<D>&);                              \
  template void split_bezier_net<D>(const Ints<D>&, int, const double*, int, double, double*, double*);
TRIVAR_INSTANTIATE(1)
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

}  // namespace trivar
