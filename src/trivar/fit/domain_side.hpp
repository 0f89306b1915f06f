#pragma once
// One side of an LR surface's parameter rectangle (or face of an LR volume's box) and the B-splines that reach
// it: what stitching and multi-block matching adapt (seed 004: "adapt the edge knot lines of A to B"). On a side
// the LR spline's trace is a spline of one dimension less; its knots in each direction along the side are the
// union of the side B-splines' knots, and knot planes ending on the side, deep enough to cross the supports of
// the first rows and spanning the whole side, make the traces of two neighbours equal without touching B-splines
// further inside.
#include <array>
#include <cmath>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include "trivar/lr/lr_spline.hpp"

namespace trivar {

// The side u_dir = lo (end 0) or u_dir = hi (end 1) of the domain; for a surface the side's own parameter is
// direction along() = 1 - dir, for a volume the face's parameters are the two directions other than dir.
struct DomainSide {
  int dir = 0;
  int end = 0;

  template <int D>
  double value(const LRSpline<D>& s) const { return end == 0 ? s.domain().lo[dir] : s.domain().hi[dir]; }
  int along() const { return 1 - dir; }
};

// The directions along a side (all but side.dir), ascending.
template <int D>
std::array<int, D - 1> along_directions(DomainSide side) {
  std::array<int, D - 1> out{};
  for (int a = 0, n = 0; a < D; ++a)
    if (a != side.dir) out[static_cast<std::size_t>(n++)] = a;
  return out;
}

// Per direction of the domain, the trace knots as (value, multiplicity), ascending; the side's own direction
// holds none.
template <int D>
using SideKnots = std::array<std::vector<std::pair<double, int>>, D>;

// The point of the side at parameter t along it.
Param<2> side_param(const LRSpline<2>& s, DomainSide side, double t);

// The Euclidean distance of two points of dim coordinates (sides are compared point by point).
inline double point_distance(const double* x, const double* y, int dim) {
  double d = 0;
  for (int k = 0; k < dim; ++k) d += (x[k] - y[k]) * (x[k] - y[k]);
  return std::sqrt(d);
}

// The diagonal of the control net's bounding box (the scale of stitching and matching tolerances).
template <int D>
double control_net_diagonal(const LRSpline<D>& s);

// Ids of the B-splines whose knots in `dir` hold the side's parameter exactly p + 1 - row times at the side's end
// of their knot vector: row 0 is non-zero on the side, row 1 adds to the derivative across it, and so on.
template <int D>
std::vector<int> side_row(const LRSpline<D>& s, DomainSide side, int row);

// The trace knots in each direction along the side, the ends included with multiplicity p + 1 (p the degree in
// that direction): an interior value's multiplicity is the most copies one row-0 B-spline holds.
template <int D>
SideKnots<D> side_trace_knots(const LRSpline<D>& s, DomainSide side);

// Inserts, for each direction along the side and each (value, multiplicity) strictly inside the side's range, a
// knot line (plane) segment across the side over the whole side, from the side inwards over the supports of rows
// 0 .. rows - 1 (LR refinement, the geometry is unchanged); rows <= 0: across the whole domain (a tensor spline
// stays one). With `part` (volumes), a plane spans only part's range in the other direction along the face (the
// common part of a face with a neighbour: the face is refined where the neighbour needs it, not across the
// whole face); part's ends must lie on mesh planes there. Returns the number of segments that changed the
// spline. Throws trivar::Error (from the LR refinement) when a segment would end inside an element.
template <int D>
int insert_side_knot_lines(LRSpline<D>& s, DomainSide side, const std::type_identity_t<SideKnots<D>>& knots, int rows,
                           const Box<D>* part = nullptr);

}  // namespace trivar
