#pragma once
// Gluing: builds the topology of a set of cells from their geometry.
//
// 1. Cell corners closer than the tolerance become one V-point (sweep over sorted x).
// 2. Cell edges with the same pair of V-points whose curves coincide (samples at equal parameters, or every
//    sample within tolerance of the other curve) become one V-curve; an edge whose samples all lie at its
//    single V-point is degenerate.
// 3. Faces with the same four V-points are matched under each of the 8 orientations consistent with the
//    corners; after aligning the twin's parametrisation, equal degrees, knots (to tol::knot relative) and
//    control points (to the tolerance) give a conforming shared V-surface. Faces that coincide geometrically
//    but whose nets differ are glued too and reported as control_nets_differ.
// 4. Remaining boundary faces of which an interior sample lies on another boundary face are reported as
//    partial_overlap (non-conforming contact, e.g. a T-junction), and stay boundary faces.
// The box faces of trimmed cells take part in neither 3 nor 4: a trimmed cell is bounded by its trimming
// faces, and the neighbours of trimmed cells are the faces their meshes share (a Boolean reports them).
// A face with an edge direction collapsed (control net of zero extent along s or t) is degenerate: it is a
// curve or a point, not a V-surface. A face can be glued to another face of the same cell (a closed ring).
#include <span>

#include "trivar/model/vcell.hpp"
#include "trivar/model/vtopology.hpp"

namespace trivar {

struct GlueOptions {
  // Model-space tolerance relative to the diagonal of the bounding box of all control points. The default
  // 1e-7 accepts geometry built independently in double precision (errors ~1e-12) and data exchanged with
  // single-precision or 8-digit files, while cells a thousandth of the model apart stay distinct.
  double relative_tolerance = 1e-7;
  // Absolute tolerance; when > 0 it replaces relative_tolerance. Either is at most 1e-3 of the diagonal.
  double absolute_tolerance = 0;
  // Samples per direction for the geometric comparison of edges and faces (>= 2).
  int samples = 5;
};

// Throws trivar::Error on bad options, a collapsed (zero-volume) cell, two coincident cells or a face of three.
VTopology glue(std::span<const VCell> cells, const GlueOptions& options = {});

}  // namespace trivar
