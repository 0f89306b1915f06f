#pragma once
// The boundary of a glued V-model as a B-rep (seed 001, Def. 3.5): the boundary V-surfaces with their edge
// adjacency. Closed when every boundary edge is used by exactly two boundary face edges (a face whose two
// edges are the same V-curve, a periodic seam, counts twice). Degenerate V-curves (collapsed to a point, e.g.
// at the apex of a triangular face) are not edges of the B-rep and are left out.
#include <array>
#include <utility>
#include <vector>

#include "trivar/model/vmodel.hpp"
#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

struct BoundaryFace {
  int surface = -1, cell = -1, face = -1;
  TensorSpline<2> geometry;     // the cell's face, in the face's (s, t) parameters
  std::array<int, 4> curves{};  // V-curves of the face edges (s start, s end, t start, t end)
  // S_s x S_t points into the cell (so an outward normal is -S_s x S_t), from the face index and the sign of
  // det J at the cell's centre.
  bool inward = false;
};

struct BoundaryEdge {
  int curve = -1;
  std::vector<std::pair<int, int>> uses;  // (index into ModelBoundary::faces, face edge 0..3)
};

struct ModelBoundary {
  std::vector<BoundaryFace> faces;
  std::vector<BoundaryEdge> edges;
  bool closed() const {
    if (faces.empty()) return false;  // nothing encloses a volume
    for (const auto& e : edges)
      if (e.uses.size() != 2) return false;
    return true;
  }
};

// Throws trivar::Error when the model is not glued.
ModelBoundary model_boundary(const VModel& model);

// Distance from x to the closest boundary face (closest_point per face, after a bounding-box cull).
double distance_to_boundary(const ModelBoundary& boundary, const double* x);

}  // namespace trivar
