#pragma once
// Block-structured multipatch view of a glued V-model, as isogeometric analysis uses it: per cell (patch) its
// six faces and what lies across each, the valence of every V-curve, the singular edges, and a watertightness
// check of the shared faces.
//
// Singular edge (definition used here): a V-curve that is
// - collapsed: degenerate (its length is below the gluing tolerance, e.g. a cell edge shrunk to a point at
//   the pole of a ball or the axis of a revolved wedge), or
// - an interior edge (every V-surface around it is shared) whose valence, the number of cells around it,
//   is not 4, the valence of every interior edge of a regular hexahedral block structure.
// Boundary edges of any valence are regular: 1 (convex), 2 (flat) and 3 (re-entrant) all occur in regular
// block structures.
#include <array>
#include <vector>

#include "trivar/model/vmodel.hpp"
#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

struct FaceLink {
  int cell = -1, face = -1;     // the face across; -1 on the model boundary or for a degenerate face
  FaceOrientation orientation;  // this face's (s, t) -> the neighbour face's
  bool conforming = true;
  bool degenerate = false;      // this face is collapsed to a curve or a point
};

struct SingularEdge {
  enum class Kind { collapsed, interior_valence };
  int curve = -1;
  Kind kind = Kind::collapsed;
  int valence = 0;
};

struct MultipatchView {
  std::vector<std::array<TensorSpline<2>, 6>> faces;  // per cell, in face order u0 u1 v0 v1 w0 w1
  std::vector<std::array<FaceLink, 6>> links;
  std::vector<int> edge_valence;  // per V-curve
  std::vector<SingularEdge> singular_edges;
};

// Throws trivar::Error when the model is not glued.
MultipatchView multipatch_view(const VModel& model);

struct WatertightReport {
  bool watertight = true;
  double max_gap = 0;                              // over all shared V-surfaces
  std::vector<std::pair<int, double>> open_surfaces;  // (V-surface, gap) with gap > tolerance
};

// Samples every shared V-surface on an n x n grid of its first half, maps the parameters to the twin with the
// recorded orientation and measures the distance of the two cells' faces at the mapped points. tolerance <= 0
// uses the gluing tolerance. Differently parametrised (non-conforming) faces report the parametric gap, so
// they count as open unless their parametrisations agree. Throws trivar::Error when not glued or n < 2.
WatertightReport check_watertight(const VModel& model, double tolerance = 0, int n = 9);

}  // namespace trivar
