#include "trivar/fit/domain_side.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "trivar/lr/tensor_expansion.hpp"

namespace trivar {

Param<2> side_param(const LRSpline<2>& s, DomainSide side, double t) {
  Param<2> u{};
  u[side.dir] = side.value(s);
  u[side.along()] = t;
  return u;
}

template <int D>
double control_net_diagonal(const LRSpline<D>& s) {
  double d = 0;
  for (int j = 0; j < s.dim(); ++j) {
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    for (const auto& b : s.basis_functions()) {
      lo = std::min(lo, b.coef[static_cast<std::size_t>(j)]);
      hi = std::max(hi, b.coef[static_cast<std::size_t>(j)]);
    }
    d += (hi - lo) * (hi - lo);
  }
  return std::sqrt(d);
}

template <int D>
std::vector<int> side_row(const LRSpline<D>& s, DomainSide side, int row) {
  const int p = s.degree(side.dir);
  const double end = side.value(s);
  std::vector<int> ids;
  for (int i = 0; i < s.num_basis(); ++i) {
    const auto& t = s.basis_function(i).knots[static_cast<std::size_t>(side.dir)];
    const auto copies = std::count(t.begin(), t.end(), end);
    const bool at_end = side.end == 0 ? t.front() == end : t.back() == end;
    if (at_end && copies == p + 1 - row) ids.push_back(i);
  }
  return ids;
}

template <int D>
SideKnots<D> side_trace_knots(const LRSpline<D>& s, DomainSide side) {
  SideKnots<D> out;
  const std::vector<int> row0 = side_row(s, side, 0);
  for (int a = 0; a < D; ++a) {
    if (a == side.dir) continue;
    std::map<double, int> mult;
    for (int id : row0) raise_knot_multiplicities(s.basis_function(id).knots[static_cast<std::size_t>(a)], mult);
    const int p = s.degree(a);
    mult[s.domain().lo[a]] = p + 1;
    mult[s.domain().hi[a]] = p + 1;
    out[static_cast<std::size_t>(a)].assign(mult.begin(), mult.end());
  }
  return out;
}

template <int D>
int insert_side_knot_lines(LRSpline<D>& s, DomainSide side, const std::type_identity_t<SideKnots<D>>& knots, int rows,
                           const Box<D>* part) {
  // The depth of the first rows: the innermost end of their supports across the side.
  double depth = rows > 0 ? side.value(s) : (side.end == 0 ? s.domain().hi[side.dir] : s.domain().lo[side.dir]);
  for (int row = 0; row < rows; ++row)
    for (int id : side_row(s, side, row)) {
      const auto& t = s.basis_function(id).knots[static_cast<std::size_t>(side.dir)];
      depth = side.end == 0 ? std::max(depth, t.back()) : std::min(depth, t.front());
    }
  std::vector<MeshRectangle<D>> lines;
  for (int a = 0; a < D; ++a)
    for (const auto& [value, m] : knots[static_cast<std::size_t>(a)]) {
      if (a == side.dir || value <= s.domain().lo[a] || value >= s.domain().hi[a]) continue;
      Param<D> lo = part ? part->lo : s.domain().lo, hi = part ? part->hi : s.domain().hi;
      lo[side.dir] = std::min(depth, side.value(s));
      hi[side.dir] = std::max(depth, side.value(s));
      lines.push_back(MeshRectangle<D>::make(a, value, lo, hi, std::min(m, s.degree(a))));
    }
  return lines.empty() ? 0 : s.insert(lines);
}

template double control_net_diagonal(const LRSpline<2>&);
template double control_net_diagonal(const LRSpline<3>&);
template std::vector<int> side_row(const LRSpline<2>&, DomainSide, int);
template std::vector<int> side_row(const LRSpline<3>&, DomainSide, int);
template SideKnots<2> side_trace_knots<2>(const LRSpline<2>&, DomainSide);
template SideKnots<3> side_trace_knots<3>(const LRSpline<3>&, DomainSide);
template int insert_side_knot_lines<2>(LRSpline<2>&, DomainSide, const SideKnots<2>&, int, const Box<2>*);
template int insert_side_knot_lines<3>(LRSpline<3>&, DomainSide, const SideKnots<3>&, int, const Box<3>*);

}  // namespace trivar
