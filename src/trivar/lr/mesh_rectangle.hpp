#pragma once
// MeshRectangle<D>: one piece of an LR box mesh, an axis-aligned (D-1)-dimensional box at a constant value in
// one direction (a mesh line for D = 2, a mesh rectangle for D = 3) with a knot multiplicity.
#include <algorithm>
#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "trivar/core/box.hpp"

namespace trivar {

template <int D>
struct MeshRectangle {
  int dir = 0;          // the direction in which the rectangle is constant
  double value = 0.0;   // its parameter in that direction
  Box<D> extent{};      // extent in the other directions; lo[dir] == hi[dir] == value
  int multiplicity = 1;

  // The rectangle {u_dir = value} x [lo, hi] (entries of lo / hi at `dir` are ignored).
  static MeshRectangle make(int dir, double value, const Param<D>& lo, const Param<D>& hi, int multiplicity = 1) {
    MeshRectangle r;
    r.dir = dir;
    r.value = value;
    r.extent.lo = lo;
    r.extent.hi = hi;
    r.extent.lo[dir] = r.extent.hi[dir] = value;
    r.multiplicity = multiplicity;
    return r;
  }

  // True when the extent meets the box `b` in a set of positive (D-1)-dimensional measure, `dir` ignored.
  bool overlaps_across(const Box<D>& b) const {
    for (int j = 0; j < D; ++j)
      if (j != dir && (extent.hi[j] <= b.lo[j] || extent.lo[j] >= b.hi[j])) return false;
    return true;
  }
  // True when the box `b`, `dir` ignored, lies within the extent.
  bool contains_across(const Box<D>& b) const {
    for (int j = 0; j < D; ++j)
      if (j != dir && (b.lo[j] < extent.lo[j] || b.hi[j] > extent.hi[j])) return false;
    return true;
  }
};

// True when the union of the rectangles rect(0), ..., rect(n - 1) (each a const MeshRectangle<D>&) at
// (dir, value) with multiplicity >= `multiplicity` covers the box `b` (its `dir` entries ignored). Unions of
// rectangles are not boxes in 3D, so coverage is decided on the cells of the grid spanned by all rectangle bounds
// inside `b`. Callers pass the few rectangles of one plane (LRSpline keeps them indexed by plane), so the cost is
// independent of the mesh size. The refinement asks this for every plane inside every support it tests, so the
// scratch lists are kept per thread instead of allocated per call.
template <int D, class Rect>
bool mesh_covers(std::size_t n, Rect&& rect, int dir, double value, const Box<D>& b, int multiplicity) {
  thread_local std::vector<const MeshRectangle<D>*> hits;
  thread_local std::array<std::vector<double>, D> cuts;
  hits.clear();
  for (std::size_t i = 0; i < n; ++i) {
    const MeshRectangle<D>& r = rect(i);
    if (r.dir == dir && r.value == value && r.multiplicity >= multiplicity && r.overlaps_across(b)) {
      if (r.contains_across(b)) return true;
      hits.push_back(&r);
    }
  }
  if (hits.empty()) return false;
  // The union's measure is at most the sum of the overlaps': when that falls short of b's cross-section (by more
  // than rounding), b is not covered, which decides most tests without the grid.
  double need = 1.0, have = 0.0;
  for (int j = 0; j < D; ++j)
    if (j != dir) need *= b.hi[j] - b.lo[j];
  for (const auto* r : hits) {
    double overlap = 1.0;
    for (int j = 0; j < D; ++j)
      if (j != dir) overlap *= std::min(r->extent.hi[j], b.hi[j]) - std::max(r->extent.lo[j], b.lo[j]);
    have += overlap;
  }
  if (have < need * (1.0 - 1e-9)) return false;
  for (int j = 0; j < D; ++j) {
    if (j == dir) continue;
    auto& c = cuts[static_cast<std::size_t>(j)];
    c.assign({b.lo[j], b.hi[j]});
    for (const auto* r : hits) {
      if (r->extent.lo[j] > b.lo[j] && r->extent.lo[j] < b.hi[j]) c.push_back(r->extent.lo[j]);
      if (r->extent.hi[j] > b.lo[j] && r->extent.hi[j] < b.hi[j]) c.push_back(r->extent.hi[j]);
    }
    std::sort(c.begin(), c.end());
    c.erase(std::unique(c.begin(), c.end()), c.end());
  }
  // Odometer over the grid cells; each cell's centre must lie in some rectangle.
  std::array<int, D> c{};
  for (;;) {
    Param<D> mid{};
    for (int j = 0; j < D; ++j)
      if (j != dir) mid[j] = 0.5 * (cuts[static_cast<std::size_t>(j)][c[j]] + cuts[static_cast<std::size_t>(j)][c[j] + 1]);
    bool inside = false;
    for (const auto* r : hits) {
      bool in = true;
      for (int j = 0; j < D && in; ++j)
        if (j != dir && (mid[j] < r->extent.lo[j] || mid[j] > r->extent.hi[j])) in = false;
      if (in) {
        inside = true;
        break;
      }
    }
    if (!inside) return false;
    int j = 0;
    for (; j < D; ++j) {
      if (j == dir) continue;
      if (++c[j] + 1 < static_cast<int>(cuts[static_cast<std::size_t>(j)].size())) break;
      c[j] = 0;
    }
    if (j == D) return true;
  }
}

// mesh_covers over a list of rectangles.
template <int D>
bool mesh_covers(std::span<const MeshRectangle<D>* const> rects, int dir, double value, const Box<D>& b,
                 int multiplicity) {
  return mesh_covers<D>(rects.size(), [&](std::size_t i) -> const MeshRectangle<D>& { return *rects[i]; }, dir, value,
                        b, multiplicity);
}

}  // namespace trivar
