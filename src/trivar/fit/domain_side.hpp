#pragma once
// One side of an LR surface's parameter rectangle and the B-splines that reach it: what stitching and
// multi-block matching adapt (seed 004: "adapt the edge knot lines of A to B"). Along a side the LR surface's
// trace is a 1D spline; its knots are the union of the side B-splines' knots along the side, and knot line
// segments ending on the side, deep enough to cross the supports of the first rows, make the traces of two
// neighbours equal without touching B-splines further inside.
#include <span>
#include <utility>
#include <vector>

#include "trivar/lr/lr_spline.hpp"

namespace trivar {

// The side u_dir = lo (end 0) or u_dir = hi (end 1) of the domain; the side's own parameter is direction 1 - dir.
struct DomainSide {
  int dir = 0;
  int end = 0;

  double value(const LRSpline<2>& s) const { return end == 0 ? s.domain().lo[dir] : s.domain().hi[dir]; }
  int along() const { return 1 - dir; }
};

// The point of the side at parameter t along it.
Param<2> side_param(const LRSpline<2>& s, DomainSide side, double t);

// The diagonal of the control net's bounding box (the scale of stitching and matching tolerances).
double control_net_diagonal(const LRSpline<2>& s);

// Ids of the B-splines whose knots in `dir` hold the side's parameter exactly p + 1 - row times at the side's end
// of their knot vector: row 0 is non-zero on the side, row 1 adds to the derivative across it, and so on.
std::vector<int> side_row(const LRSpline<2>& s, DomainSide side, int row);

// The trace knots along the side as (value, multiplicity), ascending, the ends included with multiplicity p + 1
// (p the degree along the side): an interior value's multiplicity is the most copies one row-0 B-spline holds.
std::vector<std::pair<double, int>> side_trace_knots(const LRSpline<2>& s, DomainSide side);

// Inserts, for each (value, multiplicity) strictly inside the side's range, a knot line segment across the side
// from the side inwards over the supports of rows 0 .. rows - 1 (LR refinement, the geometry is unchanged);
// rows <= 0: lines across the whole domain (a tensor spline stays one). Returns the number of segments that
// changed the spline. Throws trivar::Error (from the LR refinement) when a segment would end inside an element.
int insert_side_knot_lines(LRSpline<2>& s, DomainSide side, std::span<const std::pair<double, int>> knots, int rows);

}  // namespace trivar
