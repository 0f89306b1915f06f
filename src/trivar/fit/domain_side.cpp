#include "trivar/fit/domain_side.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace trivar {

Param<2> side_param(const LRSpline<2>& s, DomainSide side, double t) {
  Param<2> u{};
  u[side.dir] = side.value(s);
  u[side.along()] = t;
  return u;
}

double control_net_diagonal(const LRSpline<2>& s) {
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

std::vector<int> side_row(const LRSpline<2>& s, DomainSide side, int row) {
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

std::vector<std::pair<double, int>> side_trace_knots(const LRSpline<2>& s, DomainSide side) {
  const int a = side.along();
  std::map<double, int> mult;
  for (int id : side_row(s, side, 0)) {
    const auto& t = s.basis_function(id).knots[static_cast<std::size_t>(a)];
    for (std::size_t i = 0; i < t.size();) {
      std::size_t j = i;
      while (j < t.size() && t[j] == t[i]) ++j;
      int& m = mult[t[i]];
      m = std::max(m, static_cast<int>(j - i));
      i = j;
    }
  }
  const int p = s.degree(a);
  mult[s.domain().lo[a]] = p + 1;
  mult[s.domain().hi[a]] = p + 1;
  return {mult.begin(), mult.end()};
}

int insert_side_knot_lines(LRSpline<2>& s, DomainSide side, std::span<const std::pair<double, int>> knots, int rows) {
  const int a = side.along();
  // The depth of the first rows: the innermost end of their supports across the side.
  double depth = rows > 0 ? side.value(s) : (side.end == 0 ? s.domain().hi[side.dir] : s.domain().lo[side.dir]);
  for (int row = 0; row < rows; ++row)
    for (int id : side_row(s, side, row)) {
      const auto& t = s.basis_function(id).knots[static_cast<std::size_t>(side.dir)];
      depth = side.end == 0 ? std::max(depth, t.back()) : std::min(depth, t.front());
    }
  std::vector<MeshRectangle<2>> lines;
  for (const auto& [value, m] : knots) {
    if (value <= s.domain().lo[a] || value >= s.domain().hi[a]) continue;
    Param<2> lo{}, hi{};
    lo[side.dir] = std::min(depth, side.value(s));
    hi[side.dir] = std::max(depth, side.value(s));
    lines.push_back(MeshRectangle<2>::make(a, value, lo, hi, std::min(m, s.degree(a))));
  }
  return lines.empty() ? 0 : s.insert(lines);
}

}  // namespace trivar
