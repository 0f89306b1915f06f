#pragma once
// Local knot vectors of the blending functions of a T-spline. For node n and direction s (t likewise):
// degree p odd: the centre knot is the anchor's s and (p + 1) / 2 knots are taken on each side; p even: the
// anchor's two sides are the first knot on each side and p / 2 more are taken beyond them. A step towards
// east first follows the T-connect: while the current node has an east neighbour on the same anchor interval,
// the knot repeats (multiplicity); then it casts a ray in the T-image along the anchor's centre line t and
// takes the next s-edge met (an edge ending on the line counts, as in Sederberg et al. 2003); past the last
// edge of the domain the knot repeats (open end). Each blending function is then the tensor B-spline on its
// local knots, as an LRBSpline<2> with gamma 1 and homogeneous control value (w x, w y, w z, w).
#include <array>
#include <vector>

#include "trivar/lr/lr_bspline.hpp"
#include "trivar/tspline/t_spline.hpp"

namespace trivar {

// The s- and t-knots (p_k + 2 each) of every node, in node order.
std::vector<std::array<std::vector<double>, 2>> local_knot_vectors(const TSpline& ts);

// The blending functions, in node order.
std::vector<LRBSpline<2>> blending_functions(const TSpline& ts);

// Moves every node's point (x, y) to its Greville point (the mean of the p inner local knots per direction),
// leaving z and the weight: a T-spline whose blending functions sum to one then maps its parameter domain onto
// itself (linear precision), the geometry analysis on a planar parameter domain starts from.
void place_at_greville_points(TSpline& ts);

}  // namespace trivar
