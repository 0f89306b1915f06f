#pragma once
// Sharp creases inside a T-mesh: the edges between two faces of a mesh whose boundary is a subdivision crease
// (EndConditions::subd_creases) that its crease list (TMesh::crease_edges, Fusion's `100edges`) or an edge
// condition (an `ec` record) marks, taken as infinitely sharp subdivision creases. The surface is C0 across
// them, the crease curve the cubic B-spline of the crease vertices (with their knot intervals), and each side the
// surface that side has when the crease is its open crease boundary. So the mesh is cut open along them
// (`split_creases`): every crease vertex gets one copy per side wedge, each with its own copy of the control point,
// and the links across a crease become boundary links.
// The crease boundary conversion (crease_ends) and everything after it then apply unchanged.
//
// Which crease vertices are cut, and their rule (TMeshVertex::crease_rule, on every side, from the original vertex
// whatever the side's faces). A vertex is a corner when three or more sharp edges meet there (crease edges, and
// the two boundary edges of a boundary vertex), or when the mesh's crease list names it (TMesh::crease_vertices,
// Fusion's `100verts`; on a crease, on the boundary or inside): subdivision interpolates it. A vertex with two
// crease edges and no boundary takes the crease rule (the crease curve runs through it), also where the crease
// turns (one side then has one face) or runs through a star point. Sides that are not a regular crease patch (a crease vertex of other
// than two faces, a corner of other than one: irregular_crease_vertices) are evaluated by local subdivision
// (crease_face). A crease ending at a vertex inside the mesh (a dart; not creased) is cut up to that vertex, which
// stays one vertex (rule dart): a slit whose end has one fan of faces from one side to the other, moved by the
// smooth rule over that fan (the slit's two sides one edge). A creased vertex inside the mesh on no crease (a
// cone point) keeps its links and takes the corner rule. Both are irregular (evaluated by local subdivision).
// Refused (trivar::Error, one line naming the vertex): a vertex on two boundary arcs, a vertex whose links are
// not one fan.
#include <vector>

#include "trivar/tspline/t_mesh.hpp"

namespace trivar {

// The crease edges of a subdivision-crease mesh, sorted; none for Bezier end conditions (there edge conditions
// carry no geometry, as in Rhino's files).
std::vector<int> crease_edges(const TMesh& m);

// Whether split_creases changes the mesh: a subdivision-crease mesh with crease edges or creased vertices.
bool has_creases(const TMesh& m);

// The mesh cut open along its crease edges (the mesh itself when it has none). Faces, their links and the edge
// of each crease edge's first link keep their numbers; the copies of a crease vertex (TMeshVertex::split_from),
// their control points, the outside links and the edges of the second side are appended.
TMesh split_creases(const TMesh& m);

// Per vertex of a subdivision-crease mesh (after split_creases), the rule of its crease boundary: its
// crease_rule where the split set one, else corner at a vertex of one quadrilateral corner and crease at the
// other boundary vertices (the mesh's own boundary, as Fusion's SUBD_CREASES); none inside but at cone points
// (corner).
std::vector<CreaseRule> boundary_rules(const TMesh& m);

// The vertices of a subdivision-crease mesh (after split_creases) that are no regular crease patch corner: a crease
// vertex of other than two faces, a corner of other than one (cone points among them), a dart. None for Bezier end
// conditions.
std::vector<int> irregular_crease_vertices(const TMesh& m);

// A mesh's darts (creases ending inside it) and cone points (creased vertices inside it on no crease), after
// split_creases (vertex ids of that mesh, which keeps the given vertices' ids).
struct CreaseSingularities {
  std::vector<int> darts, cone_points;
};
CreaseSingularities crease_singularities(const TMesh& m);

}  // namespace trivar
