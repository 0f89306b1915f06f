#pragma once
// A T-mesh whose boundary is a subdivision crease (EndConditions::subd_creases, Fusion's SUBD_CREASES) as the
// T-mesh of the same surface with Bezier end conditions, so that charts, exact faces, star points, boundary
// ghost layers, tessellation, STEP export and analysis apply unchanged.
//
// The crease surface. On a regular boundary the Catmull-Clark crease (Hoppe et al. 1994, Biermann-Levin-Zorin
// 2000) is the uniform bicubic B-spline of the control points extended by the ghost rows P-1 = 2 P0 - P1: the
// boundary curve is the cubic B-spline of the boundary points (P0 along the boundary, corners interpolated) and
// the second derivative across the boundary is zero (the natural end). With unequal knot intervals the same two
// conditions define it here: across the boundary, on the node's knots 0 | t1 = d1 | t2 = d1 + d2 (d1 the
// interior edge, d2 the knot interval after it on the same line), the surface is the clamped cubic on
// 0, 0, 0, 0, t1, t2, ... of the rows Q0 (the end-condition block point), Q1 (the boundary vertex), Q2, ... with
//   Q0 = P0                                  (the boundary value),
//   Q1 = ((d1 + d2) P0 + d1 P1) / (2 d1 + d2) (C''(0) = 2 (D1 - D0) / t1 = 0, D0 = 3 (Q1 - Q0) / t1,
//                                             D1 = 3 (Q2 - Q1) / t2),
//   Q2 = P1, Q3 = P2, ...                    (the control point of the node at t1 is the blossom (0, t1, t2)
//                                             whatever knots lie beyond the boundary).
// No ghost interval needs choosing: an unclamped ghost row of its own knots carries both conditions only for
// particular ghost intervals (all equal to d1 when d1 = d2, where the ghost is 2 P0 - P1), and the clamped form
// is that surface. Equal intervals give Q1 = (2 P0 + P1) / 3, the inverse of boundary_ghosts' relation for the
// ghost 2 P0 - P1. A line of one interval between two boundaries takes d2 = d1 (zero second derivative at both
// ends: the straight segment). At a convex corner the rule acts in both directions (the tensor product): the
// corner's point Q11 = sum a_i b_j P_ij over the corner face's four points, the block points Q01 and Q10 the
// one-directional rule along the two boundary edges, the diagonal block point Q00 = P00 (interpolated).
// Rational points: the rules act on (w x, w); a and b are positive, so weights stay positive.
//
// Where the rows are not a tensor grid the same vertex-local rule defines the surface: d2 is the node's second
// inward knot by the T-spline's ray (the interval after the interior edge, or the depth of the face beyond a
// T-junction the edge runs into), P1 the inner end of the interior edge. The boundary curve is then still the
// B-spline of the boundary points (Q0 = P0 at every boundary vertex) and the surface a T-spline with Bezier end
// conditions (C2 wherever the T-spline is); the zero second derivative across the boundary is exact where the
// blending functions of the first three rows are tensor products of their rows. Boundary vertices that are no
// regular crease patch corner (irregular_crease_vertices: boundary star points, a crease turning at a vertex, a
// concave corner, a corner with a side of several faces) have no Bezier form: they keep their points and no
// block, and their faces are evaluated by local subdivision (crease_face, in TMeshSurface), whose rules at a
// regular crease boundary are midpoint knot insertion of this clamped form (crease_face.hpp), also with unequal
// intervals. Intervals next to a star point are taken equal (d2 = d1): the faces whose blending functions reach
// such a block are star, Catmull-Clark or crease faces, which do not read it. A block point the input carries
// at a boundary vertex is replaced.
// Sharp creases inside the mesh (sharp_creases) are cut open first, so that their sides are crease boundaries
// too. Refused (trivar::Error, one line naming the vertex): degree other than 3, a boundary vertex on two boundary
// arcs, a T-junction on the boundary (no interior edge), a convex corner whose face is not a quadrilateral, a
// boundary vertex without a control point or frame direction.
#include "trivar/tspline/t_mesh.hpp"

namespace trivar {

// Bezier end conditions with no block point anywhere (a TSM file without grip map, as Fusion writes with
// MULTIPLE_KNOTS): the repeated-knot nodes of each straight boundary vertex and convex corner are placed on the
// vertex itself (the clamped end of the boundary rows as they are; the boundary curve is the B-spline of the
// boundary points), boundary star points keep none (their ghost layer takes the vertex), a concave corner or a
// degree other than 3 is refused. Other Bezier meshes are returned as they are.
TMesh bezier_equivalent(const TMesh& m);
// The same for a mesh whose sharp creases are cut open already (split_creases), or that has none.
TMesh bezier_equivalent_of_cut(const TMesh& m);

}  // namespace trivar
