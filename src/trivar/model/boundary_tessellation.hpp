#pragma once
// Watertight adaptive tessellation of a closed B-rep whose faces are spline surfaces (the boundary of a
// V-model): every shared curve is sampled once and both faces use the same vertices, so the triangle mesh
// is closed by construction, not by welding.
#include <vector>

#include "trivar/core/box.hpp"
#include "trivar/model/brep.hpp"
#include "trivar/model/triangle_mesh.hpp"

namespace trivar {

struct TessellationOptions {
  // Largest distance between a point of the mesh and the surface, in model units.
  double chordal_tolerance = 1e-3;
};

// Where a mesh vertex came from: the face it was evaluated on and its parameters there (the first face that
// uses it), for attribute colouring.
struct VertexOrigin {
  int face = -1;
  Param<2> uv{};
};

struct BrepTessellation {
  TriangleMesh mesh;
  std::vector<VertexOrigin> origins;  // one per mesh vertex
};

// Tessellates every face by cells in its parameter domain, split where a bound on the distance between the
// surface and the cell's triangles (from the normal part of the second derivatives) exceeds the tolerance or
// where a cell is more than twice as long in space as it is wide, and graded so that no cell side meets more
// than one corner of its neighbours (on the same face or across a curve). Each cell is a fan of triangles
// from its centre, so triangles stay well shaped; a flat face keeps cells as large as its neighbours allow.
// Faces meeting along a curve cut it on a common lattice, so their vertices there are shared. Throws
// trivar::Error on an inconsistent Brep (bad ids, a curve used by sides that are more than 100 chordal
// tolerances apart at its samples, a surface that is not 3-dimensional) and, before tessellating, when the
// triangles the tolerance calls for would not fit into the available memory.
BrepTessellation tessellate(const Brep& brep, const TessellationOptions& opts = {});

}  // namespace trivar
