#pragma once
// TrimmedBoundary: the closed boundary of a solid as trimmed spline faces (seed 001: the trimming surfaces of
// a V-cell), kept two ways at once: exactly (each face a NURBS surface with trimming loops in its parameter
// domain, the shared edges as 3D curves) and as a watertight triangle mesh within a chordal tolerance whose
// triangles know their face and face parameters. The exact form gives volumes and crossing points; the mesh
// gives robust topology (inside/outside parity, candidate intersections) and output files.
//
// Coordinates are model space: a trimmed V-cell is the part of its trivariate's image inside the boundary
// (for the default cell, whose trivariate is the identity on a box around the solid, parameter and model
// points coincide).
#include <array>
#include <string>
#include <vector>

#include "trivar/core/box.hpp"
#include "trivar/model/triangle_mesh.hpp"
#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

// One use of an edge by a trimming loop: the edge's parameter-space curve on this face, oriented along the
// loop.
struct TrimCurve {
  TensorSpline<1> pcurve;  // control dimension 2: (u, v) in the face's parameter domain
  int edge = -1;           // index into TrimmedBoundary::edges; -1 for a degenerate edge (a pole)
  bool edge_reversed = false;  // the loop runs from the edge curve's end to its start
};

// A closed chain of trim curves. The face's region lies to the left of every loop in the (u, v) plane: outer
// loops run counter-clockwise, holes clockwise, whatever the face's orientation in space.
struct TrimLoop {
  std::vector<TrimCurve> curves;
};

struct TrimmedFace {
  TensorSpline<2> surface;     // control dimension 3 (NURBS in homogeneous form, as everywhere)
  std::vector<TrimLoop> loops;
  bool reversed = false;       // the outward normal of the solid is S_v x S_u instead of S_u x S_v
  double tolerance = 0;        // the source's geometric tolerance of the face (0 when exact by construction)
  std::string kind;            // the source surface kind: plane, cylinder, cone, sphere, torus, revolution,
                               // extrusion, bspline, bezier, offset, ...
  std::string name;            // how the source names the face, for messages (e.g. "#812 ADVANCED_FACE")
};

// A 3D curve shared by the faces on either side of it.
struct TrimEdge {
  TensorSpline<1> curve;  // control dimension 3
  double tolerance = 0;
};

struct TrimmedBoundary {
  std::vector<TrimmedFace> faces;
  std::vector<TrimEdge> edges;
  // Closed, consistently oriented (outward normals), shared vertices: is_watertight(mesh) holds.
  TriangleMesh mesh;
  std::vector<int> triangle_face;                    // per triangle: its face
  std::vector<std::array<Param<2>, 3>> triangle_uv;  // per triangle: the face parameters of its corners
  double chordal_tolerance = 0;                      // largest distance of the mesh from the faces
};

}  // namespace trivar
