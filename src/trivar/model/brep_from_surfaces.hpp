#pragma once
// Builds the Brep topology of a set of spline surfaces that close up a solid: corners that coincide become
// one vertex, sides that coincide become one curve, and the faces are oriented consistently and outwards.
#include <vector>

#include "trivar/model/boundary_tessellation.hpp"

namespace trivar {

struct BrepOptions {
  // Corners closer than this are one vertex; sides whose end points and quarter points agree to it are one
  // curve. In model units.
  double tolerance = 1e-9;
  // Require every curve to be used by exactly two face sides (a closed surface); otherwise open boundaries
  // are allowed and reported by Brep consumers.
  bool require_closed = true;
};

// Faces keep their order; sides are numbered as in BrepFace. A side collapsed to a point (a pole) is a
// closed curve on one vertex. Orientation: flips propagate across shared curves (neighbours must traverse
// them in opposite directions); each connected component is then turned so its enclosed volume is positive.
// Throws trivar::Error naming the face and side when a side matches no other (with require_closed), when a
// curve is shared by more than two sides, or when the faces cannot be oriented consistently (a one-sided
// surface).
Brep brep_from_surfaces(std::vector<TensorSpline<2>> surfaces, const BrepOptions& opts = {});

}  // namespace trivar
