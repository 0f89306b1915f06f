#pragma once
// How far a trimmed boundary is from closing. Its area vector A, the integral of the outward normal over the
// faces (trimmed_area_vector), is zero for a closed surface; on a boundary with a gap or a missing face it is
// minus the area vector of what is missing. Every volume by the divergence theorem (trivar's exact-boundary
// volume and a kernel's alike) then depends on its reference point c: with the field (x - c) / 3,
// V(c) - V(c') = (c' - c) . A / 3; with trivar's (x - c_x, 0, 0), V(c) - V(c') = (c'_x - c_x) A_x. A reference
// point anywhere in the bounding box thus leaves the volume uncertain by up to |A| times the box's diagonal.
#include <array>

#include "trivar/model/trimmed_boundary.hpp"

namespace trivar {

struct ClosureDefect {
  std::array<double, 3> area_vector{};  // integral of the outward normal over the faces
  double norm = 0;                      // |area_vector|
  double area = 0;                      // the boundary's area (its mesh's, within the chordal tolerance)
  double relative = 0;                  // norm / area
  double volume_uncertainty = 0;        // norm times the diagonal of the boundary's bounding box
  // The largest norm of a boundary closed within its tolerances: faces that meet along an edge within its
  // tolerance t (the edge curve within t of both) leave open at most a strip of width 2t along it, so
  // sum over edges of 2 t length, plus the quadrature's rounding (1e-10 of the area).
  double allowance = 0;
  bool closed() const { return norm <= allowance; }
};

ClosureDefect closure_defect(const TrimmedBoundary& b);

}  // namespace trivar
