#pragma once
// Star points on the boundary of a T-mesh (boundary vertices whose faces' angles exceed 270 degrees), made interior
// star points of a control mesh extended by one layer of ghost faces beyond the boundary, so that Catmull-Clark
// (Stam's exact evaluation) applies unchanged around them.
//
// Why a ghost layer, and which one. Across a straight boundary with Bezier end conditions the T-spline is the
// clamped cubic B-spline on the knots 0, 0, 0, 0, 1, 2, ... (equal intervals) of the rows Q0 (the vertex's
// end-condition block point), Q1 (the boundary vertex), Q2 (its neighbour inside), Q3, ... On t >= 0 that space
// is spanned by the uniform B-splines of the nodes -1, 0, 1, 2, ..., so the same surface is the uniform bicubic
// B-spline of the rows P-1, P0, P1, Q3, ... with (blossoms of the clamped curve at (j - 1, j, j + 1))
//   P-1 = 6 Q0 - 6 Q1 + Q2 (the ghost, one interval beyond the boundary),  P0 = (3 Q1 - Q2) / 2,  P1 = Q2,
// the rows beyond unchanged (its boundary curve (P-1 + 4 P0 + P1) / 6 = Q0, the cubic B-spline of the block
// points). Catmull-Clark on the extended mesh is that uniform bicubic B-spline wherever the mesh is regular,
// i.e. the T-spline itself, and a boundary star point of K faces becomes an interior one of K + 2 (its two ghost
// faces meet at the ghost point g of the star). For the star point the inner neighbour Q2 is the mean of the
// inner ends of its interior edges (the one across for K = 2, which makes a regular boundary vertex exact);
// Q0 its own block point (or the point itself without a block). The rules are applied to homogeneous points
// (w x, w).
//
// The boundary curve is then the cubic B-spline of the block points wherever the 4 x 4 points of the boundary's
// faces avoid the star point and g (from two faces along the boundary on); next to the star point it is the
// Catmull-Clark limit curve of the extended mesh (C1, with the tangent plane of the star point).
#include <span>
#include <vector>

#include "trivar/tspline/t_mesh.hpp"

namespace trivar {

struct GhostedMesh {
  TMesh mesh;                 // the input with ghost vertices, points, links and faces appended (input ids kept)
  std::vector<int> ghost;  // per input vertex: its ghost vertex in `mesh` (its own point there is P0), -1: none
};

// Ghost layers along the boundary from each star point in `stars` (boundary vertices), up to `reach` edges either
// way, stopping before a boundary vertex that is not straight (two faces, no T-junction, one block point). Layers
// that meet (star points within 2 reach edges along the boundary, or the two ends of a slit) are one layer through
// both star points, closed when it covers a whole boundary loop.
// Throws trivar::Error (one line) when a star point has more than one boundary arc or no straight neighbour on
// either side, a vertex of the layer has no single block point, or a weight of the extended mesh is not positive.
GhostedMesh ghost_boundary(const TMesh& m, std::span<const int> stars, int reach);

}  // namespace trivar
