#pragma once
// Sharp creases inside a T-mesh: the edges between two faces of a mesh whose boundary is a subdivision crease
// (EndConditions::subd_creases) that its crease list (TMesh::crease_edges, Fusion's `100edges`) or an edge
// condition (an `ec` record) marks, taken as infinitely sharp subdivision creases. The surface is C0 across
// them, the crease curve the cubic B-spline of the crease vertices (with their knot intervals), and each side the
// surface that side has when the crease is its open crease boundary. So the mesh is cut open along them (`split_creases`): every crease vertex gets one copy per
// side wedge, each with its own copy of the control point, and the links across a crease become boundary links.
// The crease boundary conversion (crease_ends) and everything after it then apply unchanged.
//
// Which crease vertices are cut. A vertex is corner-like when three or more sharp edges meet there (crease
// edges, and the two boundary edges of a boundary vertex): subdivision interpolates it (the corner rule), and
// every side wedge must be a convex corner (one face, 90 degrees) for crease_ends' corner rule. A vertex with
// two crease edges and no boundary takes the crease rule (the crease curve runs smoothly through it): both
// wedges must be straight (180 degrees), since crease_ends would make a 90-degree wedge a corner and refuses
// 270 degrees. Refused (trivar::Error, one line naming the vertex): a crease ending at an interior vertex (a
// dart: subdivision smooths there and the cut is undefined), a crease turning at a vertex of two crease edges,
// a crease through a star point, a corner-like vertex with a side wedge of other than one face, a vertex whose
// links are not one fan.
#include <vector>

#include "trivar/tspline/t_mesh.hpp"

namespace trivar {

// The crease edges of a subdivision-crease mesh, sorted; none for Bezier end conditions (there edge conditions
// carry no geometry, as in Rhino's files).
std::vector<int> crease_edges(const TMesh& m);

// The mesh cut open along its crease edges (the mesh itself when it has none). Faces, their links and the edge
// of each crease edge's first link keep their numbers; the copies of a crease vertex (TMeshVertex::split_from),
// their control points, the outside links and the edges of the second side are appended.
TMesh split_creases(const TMesh& m);

}  // namespace trivar
