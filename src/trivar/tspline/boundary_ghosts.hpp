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
// Corners (a boundary vertex of one face). With Bezier end conditions the T-spline near a corner is the tensor
// product of two clamped ends: on the 3 x 3 rows Q(i, j) (i = 0 block, 1 boundary, 2 inside, across each side)
// it is the uniform bicubic B-spline of P = (M x M) Q with M the rule above. So the layer goes round the corner:
// the corner's point becomes P(0, 0) = 9/4 Q11 - 3/4 (Q12 + Q21) + 1/4 Q22, it gets a ghost across each side and a
// diagonal one (its block's three points Q01, Q10, Q00 enter these), and a ghost face (corner, ghost, diagonal
// ghost, ghost) joins the two sides' ghost faces, where the corner is a regular vertex of the extended mesh. The
// neighbours' rows across the sides are their own rows of the straight rule, which is the product exactly (their
// inner neighbour is the corner face's far corner); a star point one edge from the corner enters with its own
// rows (the product taken across its side first), so the corner's limit point is still its diagonal block point
// Q00 and the boundary curve along its other side the cubic B-spline of the block points.
//
// The boundary curve is then the cubic B-spline of the block points wherever the 4 x 4 points of the boundary's
// faces avoid the star point and g (from two faces along the boundary on); next to the star point it is the
// Catmull-Clark limit curve of the extended mesh (C1, with the tangent plane of the star point).
//
// Unequal knot intervals. Across the boundary the clamped cubic has knots 0, 0, 0, 0, d1, d1 + d2, ... at a vertex
// (d1, d2 the intervals into the mesh along its interior edge; a star point's mean over its interior edges; a
// corner's along each side), and any knots -2 g, -g beyond the boundary span the same curve on t >= 0. With g the
// interval into the mesh that most of the layer's vertices have (every interval when they are equal, giving the
// rule above; faces whose 4 x 4 points read the layer take the uniform rules only where g is their interval too,
// TMeshSurface) the ghost
// rows are the blossoms P-1 = c(-2 g, -g), P0 = c(-g, d1) of the first piece, with one argument 0 a quadratic
// c(x, y) = A + B (x + y) + C x y fixed by Q0 = c(0, 0), Q1 = c(0, d1), Q2 = c(d1, d1 + d2). The ghost faces'
// sides across the boundary get the interval g, so every strip has one interval; beyond the ghost row the knots
// repeat g (the natural end of a crease boundary of the extended mesh: knot reads and local subdivision there,
// TMeshSurface).
#include <span>
#include <vector>

#include "trivar/tspline/homogeneous_point.hpp"
#include "trivar/tspline/t_mesh.hpp"

namespace trivar {

// The 1-D rule across a straight boundary with Bezier end conditions: the ghost row P-1 and the boundary row P0
// that replace the clamped cubic's rows q0 (the end-condition block point), q1 (the boundary vertex), q2 (the row
// inside) on the intervals d1, d2 into the mesh, for the ghost interval g (the rows beyond stay).
struct GhostRows {
  HomogeneousPoint ghost, point;
};
GhostRows clamped_end_rows(const HomogeneousPoint& q0, const HomogeneousPoint& q1, const HomogeneousPoint& q2, double d1, double d2, double g);

struct GhostedMesh {
  TMesh mesh;                 // the input with ghost vertices, points, links and faces appended (input ids kept; the
                              // boundary links the ghost faces replace are deleted slots)
  // per input vertex: its ghost vertex in `mesh` across the boundary link leaving it (its own point there is P0;
  // a corner's P(0, 0)), -1: none
  std::vector<int> ghost;
  double interval = 1;  // the ghost faces' knot interval across the boundary
};

// Ghost layers over the boundary links whose two vertices lie within `reach` steps across faces from a star point
// of `stars` (on a grid the larger of the two index distances: on a straight boundary `reach` edges; star points
// inside the mesh place layers too) and that the layer runs through: straight vertices (two faces, no T-junction,
// one block point), corners whose neighbours along the boundary are straight or star points (sides of one edge
// and T-junctions stop it) and the star points on the boundary. Layers that meet (star points within 2 reach
// edges along the boundary, or the two ends of a slit) are one layer through both star points, closed when it
// covers a whole boundary loop. A run of the layer without a boundary star point is left out where a vertex has
// no end-condition nodes (no single block point; a corner: no block of three).
// Throws trivar::Error (one line) when a star point on the boundary has more than one boundary arc, no link of the
// layer on either side or another star point next to it, a vertex of its run has no single block point (a
// corner: no block of three), or a weight of the extended mesh is not positive.
GhostedMesh ghost_boundary(const TMesh& m, std::span<const int> stars, int reach);

}  // namespace trivar
