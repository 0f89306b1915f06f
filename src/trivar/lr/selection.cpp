#include "trivar/lr/selection.hpp"

#include <algorithm>
#include <limits>
#include <string>

#include "trivar/core/error.hpp"

namespace trivar {

std::vector<int> checked_ids(std::span<const int> ids, int count, const char* what) {
  std::vector<int> out(ids.begin(), ids.end());
  for (int i : out)
    require(i >= 0 && i < count, [&] {
      return std::string(what) + " id " + std::to_string(i) + " outside 0.." + std::to_string(count - 1);
    });
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

template <int D>
bool segment_meets_open(const Param<D>& p0, const Param<D>& p1, const Box<D>& b) {
  // The open interval (t_lo, t_hi) of t where the point is strictly inside, intersected with [0, 1].
  double t_lo = -std::numeric_limits<double>::infinity(), t_hi = std::numeric_limits<double>::infinity();
  for (int k = 0; k < D; ++k) {
    const double d = p1[k] - p0[k];
    if (d == 0.0) {
      if (!(b.lo[k] < p0[k] && p0[k] < b.hi[k])) return false;
      continue;
    }
    double a = (b.lo[k] - p0[k]) / d, c = (b.hi[k] - p0[k]) / d;
    if (a > c) std::swap(a, c);
    t_lo = std::max(t_lo, a);
    t_hi = std::min(t_hi, c);
  }
  return t_lo < t_hi && t_lo < 1.0 && t_hi > 0.0;
}

namespace {

template <int D, class Test>
std::vector<int> select(int n, Test&& test) {
  std::vector<int> out;
  for (int i = 0; i < n; ++i)
    if (test(i)) out.push_back(i);
  return out;
}

}  // namespace

template <int D>
std::vector<int> elements_in_box(const LRSpline<D>& lr, const Box<D>& q) {
  return select<D>(lr.num_elements(), [&](int e) { return box_meets_open(q, lr.element(e)); });
}

template <int D>
std::vector<int> functions_in_box(const LRSpline<D>& lr, const Box<D>& q) {
  return select<D>(lr.num_basis(), [&](int b) { return box_meets_open(q, lr.basis_function(b).support()); });
}

template <int D>
std::vector<int> elements_on_segment(const LRSpline<D>& lr, const Param<D>& p0, const Param<D>& p1) {
  return select<D>(lr.num_elements(), [&](int e) { return segment_meets_open<D>(p0, p1, lr.element(e)); });
}

template <int D>
std::vector<int> functions_on_segment(const LRSpline<D>& lr, const Param<D>& p0, const Param<D>& p1) {
  return select<D>(lr.num_basis(),
                   [&](int b) { return segment_meets_open<D>(p0, p1, lr.basis_function(b).support()); });
}

#define TRIVAR_INSTANTIATE(D)                                                                                      \
  template bool segment_meets_open<D>(const Param<D>&, const Param<D>&, const Box<D>&);                            \
  template std::vector<int> elements_in_box(const LRSpline<D>&, const Box<D>&);                                   \
  template std::vector<int> functions_in_box(const LRSpline<D>&, const Box<D>&);                                  \
  template std::vector<int> elements_on_segment(const LRSpline<D>&, const Param<D>&, const Param<D>&);            \
  template std::vector<int> functions_on_segment(const LRSpline<D>&, const Param<D>&, const Param<D>&);
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

}  // namespace trivar
