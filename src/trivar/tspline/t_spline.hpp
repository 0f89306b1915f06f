#pragma once
// TSpline: a T-spline surface as the three layers of Xiao et al. 2016 (seed 002): the parametric T-image,
// the topological T-connect and the cartesian T-pointset, with a degree per direction (any, odd or even).
// Each T-node is one blending function: a tensor B-spline on the local knot vectors deduced from the
// T-connect and the T-image (local_knots.hpp), weighted by its point's weight.
#include <string>

#include "trivar/core/box.hpp"
#include "trivar/tspline/t_connect.hpp"
#include "trivar/tspline/t_image.hpp"
#include "trivar/tspline/t_pointset.hpp"

namespace trivar {

struct TSpline {
  std::string name;
  Ints<2> degrees{3, 3};
  bool force_bezier = true;  // the exporter's end-condition flag, kept for exchange
  TImage image;
  TConnect connect;
  TPointset pointset;
};

// The anchor of a node as a box in (s, t): a vertex is a point, a link its edge, a face its rectangle.
Box<2> anchor_box(const TSpline& ts, const TNode& n);

// Throws trivar::Error naming the first inconsistency: the T-image (validate(TImage)), degrees outside
// 1..kMaxDegree, a node whose anchor or point does not exist, a node whose anchor does not match the degree
// parities (an odd direction needs an anchor of zero width, an even one a face-wide or zero-width anchor), a
// neighbour id out of range or the node itself (neighbours need not point back: the seed-002 prototype links
// the outer nodes of repeated-knot blocks one way), a weight that is not positive and finite.
void validate(const TSpline& ts);

}  // namespace trivar
