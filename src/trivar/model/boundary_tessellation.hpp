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
  // Largest distance between the surface and the chord / triangle midpoints that is accepted, in model units.
  double chordal_tolerance = 1e-3;
  // Upper bound of samples per curve and of grid lines per face direction, a guard against degenerate input.
  int max_samples = 4096;
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

// Tessellates every face: each curve is sampled adaptively (starting from the knots of the sides on it)
// until the chordal error is below the tolerance on every face that uses it; each face gets a tensor grid of
// interior parameters refined the same way (chords along both grid directions and quad centres) and a
// strip that zips its boundary samples to the first interior grid ring. Vertices of shared curves and
// corners are shared. Throws trivar::Error on an inconsistent Brep (bad ids, a curve used by sides that are more
// than 100 chordal tolerances apart at its samples, a surface that is not 3-dimensional).
BrepTessellation tessellate(const Brep& brep, const TessellationOptions& opts = {});

}  // namespace trivar
