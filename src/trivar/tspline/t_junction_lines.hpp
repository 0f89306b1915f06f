#pragma once
// T-junctions near star points, completed into knot lines. Within p rings of a star point's faces a T-junction has
// no evaluation rule of its own: the T-spline's blending functions there reach the star point, and the Catmull-Clark
// rules (uniform, non-uniform, local subdivision) take quadrilaterals only; two rings further out it still lies
// among the points of faces that take those rules (TMeshSurface completes the lines of both). The same holds near the
// irregular vertices of a crease boundary (darts, crease corners of other than one face), whose faces local
// subdivision takes. trivar continues each
// such T-junction's missing edge through the face it points into, and on through the faces beyond, until the line
// meets a vertex: where it crosses an edge it inserts a vertex, and the control points of the row of that edge (the
// line of edges through it, straight through vertices of four faces) follow Boehm's knot insertion of the cubic on
// the row's knot intervals (the interval past a star point is nurcc_across's, as in the subdivision rules). Wherever
// the T-spline's blending functions are tensor B-splines along those rows this is knot insertion, which leaves the
// surface unchanged (tests/tspline/t_junction_lines_test.cpp); next to a star point, where no T-spline exists, it
// defines the surface as that of the completed mesh, whose faces the Catmull-Clark rules then take. The completed
// mesh is no longer the T-mesh as given: its faces are pieces of the given ones (FacePiece).
//
// No row goes straight through a star point. A line that crosses one of its spokes takes, as the row's node beyond
// the star point, the backward spokes' nodes weighted by max(0, -cos) of their angle to the crossed spoke (and the
// intervals after them so), the weights nurcc_across gives the interval there; at four faces that would be the
// opposite spoke's row. Only the star point's own point depends on it. A star point on a Bezier boundary has its
// fan closed by its ghost layer's spoke (boundary_ghosts' clamped-end row). A row that ends at the stem of another
// T-junction goes on along that T-junction's line, which is completed first; the line that needed it goes on from
// where it stopped.
//
// At a Bezier boundary a row ends in its end-condition node, at the boundary vertex's knot (clamped): the insertion
// takes it as the row's end node, and a line that reaches the boundary ends there. A row along the boundary has the row
// of its end-condition nodes outside (the boundary curve's control points) beside it, which takes the same insertion
// (at a convex corner ending in the corner's diagonal node), and gives the new boundary vertex its node; without a grip
// map the nodes lie on the vertices, where bezier_equivalent places them. At a subdivision crease (Fusion's
// SUBD_CREASES boundary, and the sides of sharp creases, on the mesh cut open along them) a row ends in the crease's
// natural end, zero second derivative across it: the insertion acts on its clamped form (crease_ends: the node at the
// boundary vertex is Q1 = a P0 + b P1), which it keeps, so the boundary vertex keeps its point and the refined row is
// again a natural end. A line that reaches a side of a sharp crease goes on from the same place of the other side,
// whose copy of the crease row gets the same insertion (as the T-spline's line would cross the crease's knot line):
// both sides keep one crease curve and one set of vertices on it. tests/tspline/t_junction_lines_test.cpp checks all of
// these against the cage without the T-junctions.
//
// A row through a dart (a sharp crease ending inside, cut open up to it) or a cone point (a corner inside the mesh)
// passes it as through any vertex of its fan (straight on where its faces make four quarter turns, else as through a
// star point): the dart's fan closed across its slit, the slit's two spokes one. The dart is one vertex of both sides of the slit: the second side's insertion
// along a crease row through it starts from its point before the first's. A sharp edge between two darts has both
// sides between the same two vertices; they are kept apart (across, and the completed mesh's links).
//
// Scope: degree 3; the rows the lines cross must pass no irregular vertex of a crease boundary other than darts
// and cone points (a crease corner of other than one face; where a crease turns or runs through a star point, only
// the row along the crease), no concave corner, carry one control point per vertex (and
// the end-condition nodes the grip map gives their boundary vertices), and a row on a sharp crease's second side must
// not end at a T-junction's stem (its first side is split by then); anything else is refused in one line naming the
// T-junction and the cause.
#include <array>
#include <optional>
#include <vector>

#include "trivar/tspline/t_mesh.hpp"

namespace trivar {

// A face of the completed mesh within a face of the mesh as given: that face, and the rectangle lo + [0, size]
// in its (u, v) (frames of the same orientation: the piece's first corner link runs along the given face's u).
struct FacePiece {
  int source = -1;
  std::array<double, 2> lo{0, 0}, size{1, 1};
};

struct CompletedLines {
  TMesh mesh;
  TMesh welded;                   // a mesh cut along sharp creases: `mesh` with the creases' sides joined again
  std::vector<FacePiece> pieces;  // per face of `mesh`
  int lines = 0;                  // T-junction lines completed
  int vertices = 0;               // vertices inserted
};

// The mesh with the lines of its T-junctions within `rings` face rings of the faces of a star point, rings + 1 of an
// irregular crease-boundary vertex's, and on the face at a corner of a crease boundary completed; `m` is cut open
// along its sharp creases (split_creases) if it has any. Empty when it has none. Deleted faces (empty loops) have no
// piece.
std::optional<CompletedLines> complete_t_junction_lines(const TMesh& m, int rings);

}  // namespace trivar
