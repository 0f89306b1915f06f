#pragma once
// Selecting elements or B-splines of an LR spline to refine: by id, by a parameter box, by a segment between
// two parameter points. Geometric selections use OPEN interiors (element interiors, open supports): a box or
// segment that only touches a face, edge or corner selects nothing, so the diagonal of a uniform mesh selects
// exactly the elements it crosses. Results are ascending ids without duplicates.
#include <span>
#include <vector>

#include "trivar/core/box.hpp"
#include "trivar/lr/lr_spline.hpp"

namespace trivar {

// The ids sorted and deduplicated; throws trivar::Error naming the first id outside 0..count-1 (what: "element").
std::vector<int> checked_ids(std::span<const int> ids, int count, const char* what);

// True when the closed box q meets the open box b (every k: q.lo < b.hi and b.lo < q.hi).
template <int D>
bool box_meets_open(const Box<D>& q, const Box<D>& b) {
  for (int k = 0; k < D; ++k)
    if (!(q.lo[k] < b.hi[k] && b.lo[k] < q.hi[k])) return false;
  return true;
}

// True when the closed segment p0-p1 meets the open box b: some t in [0, 1] with b.lo < p0 + t (p1 - p0) < b.hi
// in every direction. The open t-intervals per direction are intersected as exact comparisons of
// (b.lo - p0) / d; they are exact whenever these quotients are (e.g. dyadic boxes on the unit diagonal).
template <int D>
bool segment_meets_open(const Param<D>& p0, const Param<D>& p1, const Box<D>& b);

template <int D>
std::vector<int> elements_in_box(const LRSpline<D>& lr, const Box<D>& q);
template <int D>
std::vector<int> functions_in_box(const LRSpline<D>& lr, const Box<D>& q);
template <int D>
std::vector<int> elements_on_segment(const LRSpline<D>& lr, const Param<D>& p0, const Param<D>& p1);
template <int D>
std::vector<int> functions_on_segment(const LRSpline<D>& lr, const Param<D>& p0, const Param<D>& p1);

}  // namespace trivar
