#pragma once
// The V-topology of trimmed cells across their trimming faces (seed 001, Defs. 3.4-3.5): which face of which
// cell a trimming face is shared with. Cells cut from one another by a Boolean (or a split) share the
// triangulation of every face between them, so a shared face's mesh triangles appear in both cells with the
// same corners (bit for bit) and opposite orientations; the faces are matched through those triangles. A face
// all of whose triangles pair with triangles of one face of another cell is an interior V-surface shared by
// exactly those two cells; a face none of whose triangles pair is a boundary V-surface; anything else (some
// triangles paired, or paired with several faces) is a non-conforming contact, reported rather than guessed.
//
// V-curves and V-points complete the topology: the cells' trimming edges (trimmed_vertices.hpp gives each
// cell's vertices from its loops) are merged across cells where their ends and interior points coincide
// within the tolerance, so an edge where faces of several cells meet is one V-curve naming every cell's edge
// on it and every V-surface bounded by it; the edges' end vertices merged alike are the V-points.
#include <array>
#include <string>
#include <vector>

#include "trivar/model/vmodel.hpp"

namespace trivar {

struct TrimmedFaceRef {
  int cell = -1, face = -1;  // face: index into the cell's TrimmedBoundary::faces
  bool operator==(const TrimmedFaceRef&) const = default;
};

struct TrimmedInterfaces {
  // Per cell, per trimming face: the face of another cell it is shared with ({-1, -1}: a boundary face or a
  // non-conforming one). Untrimmed cells have no entries.
  std::vector<std::vector<TrimmedFaceRef>> twin;
  // V-surfaces: each shared pair once (halves[0] the lower cell), then each boundary face ({face, {-1, -1}}).
  std::vector<std::array<TrimmedFaceRef, 2>> surfaces;
  int shared = 0, boundary = 0;
  // Faces only partly covered by another cell's triangles, or covered by several faces: the first cell's face.
  std::vector<TrimmedFaceRef> non_conforming;
  // Per cell: the cells it shares a face with, ascending.
  std::vector<std::vector<int>> neighbours;

  // V-curves and V-points in the types of the untrimmed topology (vtopology.hpp): CellEdgeRef::edge indexes
  // the cell's TrimmedBoundary::edges (reversed: the edge runs from VCurve::points[1] to points[0]),
  // VCurve::surfaces indexes `surfaces` above, CellCornerRef::corner numbers the cell's vertices as
  // trimmed_vertices() does.
  std::vector<VCurve> curves;
  std::vector<VPoint> points;
  std::vector<std::vector<int>> edge_curve;    // per cell, per trimming edge: its V-curve, -1 when no loop uses it
  std::vector<std::vector<int>> vertex_point;  // per cell, per vertex: its V-point
  // Per cell: V - E + sum over faces of (2 - loops) of its own boundary (2 for a ball-like cell, 0 untrimmed).
  std::vector<int> cell_euler;
  // The same over the model's boundary: the boundary V-surfaces, the V-curves bounding them and their V-points
  // (2 per sphere-like boundary component, 0 per torus-like one).
  int boundary_euler = 0;
  double tolerance = 0;  // distance under which edge ends and points of edges are taken as one
  // Inconsistencies, one line each: a cell's edge used by an odd number of face loops (a closed boundary uses
  // every edge twice), an edge end farther than the tolerance from its V-point.
  std::vector<std::string> defects;
};

// Per triangle of the concatenated trimming meshes of the trimmed cells (cell by cell, in mesh order): the
// index of the triangle of another cell with the same corners in opposite orientation, -1 for none.
// `first_triangle` receives per cell the index of its first triangle (size cells + 1).
std::vector<long> paired_trimming_triangles(const VModel& model, std::vector<long>& first_triangle);

// The shared and boundary trimming faces of the model's trimmed cells.
TrimmedInterfaces trimmed_interfaces(const VModel& model);

}  // namespace trivar
