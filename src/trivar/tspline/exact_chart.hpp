#pragma once
// Charts in which faces of a T-mesh with star points or irregular crease vertices are evaluated as the T-spline
// itself (TMeshSurface's exact faces): a set of faces laid out in the plane by their knot intervals
// (t_spline_chart), the T-spline built on it (its Bezier elements on the members alone), and the members, the
// faces it is accepted for. A member's value is the T-spline's wherever the chart holds the knot vectors of every
// blending function nonzero on it; a chart's border inside the mesh can cut them (its rays stop there as at the
// mesh's boundary), which exact_chart reports per member.
#include <array>
#include <memory>
#include <span>
#include <vector>

#include "trivar/tspline/t_mesh.hpp"
#include "trivar/tspline/t_spline_surface.hpp"

namespace trivar {

struct ExactChart {
  std::unique_ptr<TSplineSurface> surface;
  // Per member: its first corner (the first corner link of its loop) and its sides to the next and the last
  // corner, in the chart's (s, t).
  struct Frame {
    std::array<double, 2> origin, axis_u, axis_v;
  };
  std::vector<Frame> frames;
  // Per member: a blending function nonzero on it has a knot vector cut by the chart's border inside the mesh: an
  // edge of the chart with a face outside the chart on its other side lies in its support box's interior, or one of
  // its rays stops at such an edge (the knot repeats there where the mesh's ray goes on) and the member lies on the
  // knot spans whose pieces depend on the knots lost.
  std::vector<char> cut;
  // Per member: one Bezier element of the chart (no knot line of the chart crosses it; in a large chart, lines of
  // faces far away with other knot intervals can, which splits its patches without changing its surface).
  std::vector<char> whole;
};

// The chart of `faces` (those reached from `seed` across shared edges; t_spline_chart) and its members, the
// T-spline built with `threads` (parallel_for). Throws trivar::Error when the faces do not lay out (a star point
// among them, contradictory knot intervals).
ExactChart exact_chart(const TMesh& m, std::span<const int> faces, int seed, std::span<const int> members, int threads);

// The faces of a chart grown from `seed` across shared edges over the faces `allowed` (per face, nonzero:
// allowed), breadth first: each face is laid out from the neighbour that reached it and left out when that layout
// contradicts a vertex already laid out (the chart would close round a star point) or overlaps a face taken
// (round a vertex whose faces' angles exceed 360 degrees, which the knot intervals lay out over themselves). So
// the faces taken lie side by side in the plane as in the mesh, which t_spline_chart's layout does not check:
// the rays of an overlapping chart would meet knot lines of faces that are not next to them.
std::vector<int> embedded_faces(const TMesh& m, int seed, std::span<const char> allowed);

}  // namespace trivar
