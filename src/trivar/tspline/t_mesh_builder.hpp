#pragma once
// T-splines from a drawn T-mesh: the T-image from axis-parallel knot segments (vertices at every end point and
// crossing, edges between consecutive vertices of a segment, faces traced counter-clockwise), and the T-connect
// of any degrees: nodes where the parities put them (Xiao et al. 2016: odd x odd on vertices, odd x even on
// the links along the even direction, even x even on faces) plus, on the domain's boundary, the repeated-knot
// node layers of open (Bezier) end conditions: an odd direction (p - 1) / 2 layers beyond the boundary node
// (as Rhino's force-bezier export), an even one p / 2 nodes of zero width on the boundary line.
#include <array>
#include <functional>
#include <span>
#include <vector>

#include "trivar/tspline/t_spline.hpp"

namespace trivar {

struct KnotSegment {
  std::array<double, 2> from{}, to{};  // axis-parallel, from != to
};

// Throws trivar::Error for a segment that is not axis-parallel or has no length, or when the faces traced are
// not rectangles (a dangling segment end inside a face).
TImage t_image_from_segments(std::span<const KnotSegment> segments);

// The domain must be a rectangle. point(s, t, layer_s, layer_t) gives the rational point of the node anchored
// at (s, t) (the centre of its vertex, link or face) and boundary layer (0 on the anchor itself, counted
// inwards).
TSpline t_spline_from_segments(const Ints<2>& degrees, std::span<const KnotSegment> segments,
                               const std::function<RationalPoint(double, double, int, int)>& point);

}  // namespace trivar
