#pragma once
// TrimmedSolid: the region enclosed by a TrimmedBoundary, with the queries every consumer of a trimmed V-cell
// needs: is a point inside, where does a line cross the boundary, how large is the region. Immutable after
// construction and thread-safe, so cells share one through a shared_ptr.
#include <array>
#include <vector>

#include "trivar/core/box.hpp"
#include "trivar/model/trimmed_boundary.hpp"

namespace trivar {

struct LineCrossing {
  double t = 0;           // line parameter: the point is origin + t * direction
  bool entering = false;  // the line enters the region here (leaves it otherwise)
  int face = -1;          // the boundary face crossed
  Param<2> uv{};          // its parameters on that face
};

class TrimmedSolid {
public:
  // Validates the boundary (watertight, outward oriented, per-triangle data consistent, faces of control
  // dimension 3) and builds the search structures. Throws trivar::Error naming the first defect.
  explicit TrimmedSolid(TrimmedBoundary boundary);

  const TrimmedBoundary& boundary() const { return boundary_; }
  // Box around the exact faces (not only the mesh).
  const Box<3>& bounding_box() const { return box_; }

  // Whether x lies inside. Decided on the mesh by a parity count that treats rays through vertices and edges
  // consistently (so the answer never depends on luck with tangent rays); within the chordal tolerance of the
  // boundary the exact faces decide.
  bool contains(const std::array<double, 3>& x) const;

  // The crossings of the line origin + t * direction with the boundary for t in (t_lo, t_hi), sorted by t,
  // entering and leaving alternately (the first one leaving when origin + t_lo * direction is inside). Each
  // position is refined onto the exact face; a tangential touch is no crossing. `out` is cleared first.
  void crossings(const std::array<double, 3>& origin, const std::array<double, 3>& direction, double t_lo,
                 double t_hi, std::vector<LineCrossing>& out) const;

  // Volume of the region from the exact faces (divergence theorem over the trimmed parameter domains).
  double volume() const;

private:
  TrimmedBoundary boundary_;
  Box<3> box_;
};

}  // namespace trivar
