#pragma once
// Topology of a V-model (seed 001, Defs. 3.4-3.8): V-surfaces (a boundary face of one cell or a face shared by
// two), half-V-surfaces (one cell's side of a V-surface, linked to its twin), V-curves (shared by any number of
// V-surfaces) and V-points.
//
// Index conventions of a cell (a trivariate with directions 0, 1, 2 = u, v, w):
// - face f = 2 d + side, i.e. 0 u0, 1 u1, 2 v0, 3 v1, 4 w0, 5 w1. A face is parametrised by the two remaining
//   directions in increasing order, (s, t) (as iso_extract / boundary_faces give it);
// - face edges k = 0 (s = start), 1 (s = end), 2 (t = start), 3 (t = end); face corners i + 2 j (s side i,
//   t side j);
// - corner c = i0 + 2 i1 + 4 i2 (side per direction);
// - edge along direction e with the other two directions o1 < o2 at sides x1, x2: 4 e + x1 + 2 x2. An edge
//   runs from its corner with side 0 in direction e to the one with side 1.
#include <array>
#include <string>
#include <vector>

#include "trivar/core/box.hpp"

namespace trivar {

inline int face_direction(int face) { return face / 2; }
inline int face_side(int face) { return face % 2; }
// The face's parameter directions (s, t) as cell directions.
inline std::array<int, 2> face_param_dirs(int face) {
  const int d = face / 2;
  return d == 0 ? std::array<int, 2>{1, 2} : d == 1 ? std::array<int, 2>{0, 2} : std::array<int, 2>{0, 1};
}
// Cell corner at face corner (s side i, t side j).
inline int face_corner(int face, int i, int j) {
  const auto [a, b] = face_param_dirs(face);
  return (face_side(face) << face_direction(face)) | (i << a) | (j << b);
}
inline int edge_direction(int edge) { return edge / 4; }
// Cell edge along direction e whose other directions are at the sides given by `corner` (bit k = side in k).
inline int edge_through(int e, int corner) {
  const int o1 = e == 0 ? 1 : 0, o2 = e == 2 ? 1 : 2;
  return 4 * e + ((corner >> o1) & 1) + 2 * ((corner >> o2) & 1);
}
// Cell edge of face edge k (0: s = start, 1: s = end, 2: t = start, 3: t = end).
inline int face_edge(int face, int k) {
  const auto [a, b] = face_param_dirs(face);
  const int fixed = k < 2 ? a : b, along = k < 2 ? b : a;
  return edge_through(along, (face_side(face) << face_direction(face)) | ((k & 1) << fixed));
}
// Start and end corners of a cell edge.
inline std::array<int, 2> edge_corners(int edge) {
  const int e = edge / 4, x1 = edge & 1, x2 = (edge >> 1) & 1;
  const int o1 = e == 0 ? 1 : 0, o2 = e == 2 ? 1 : 2;
  const int c = (x1 << o1) | (x2 << o2);
  return {c, c | (1 << e)};
}

// How a face's normalised parameters (s, t) in [0, 1]^2 map to its twin's (s', t'): (a, b) = swap ? (t, s) :
// (s, t), then s' = flip_s ? 1 - a : a, t' = flip_t ? 1 - b : b. The eight values are the symmetries of the square.
struct FaceOrientation {
  bool swap = false, flip_s = false, flip_t = false;

  Param<2> map(const Param<2>& st) const {
    const double a = swap ? st[1] : st[0], b = swap ? st[0] : st[1];
    return {flip_s ? 1 - a : a, flip_t ? 1 - b : b};
  }
  FaceOrientation inverse() const { return {swap, swap ? flip_t : flip_s, swap ? flip_s : flip_t}; }
  int code() const { return (swap ? 4 : 0) | (flip_s ? 1 : 0) | (flip_t ? 2 : 0); }
  static FaceOrientation from_code(int c) { return {(c & 4) != 0, (c & 1) != 0, (c & 2) != 0}; }
  bool operator==(const FaceOrientation&) const = default;
};

// One cell's side of a V-surface. Half index = 6 * cell + face, so every cell face has one.
struct HalfVSurface {
  int cell = -1, face = -1;
  int surface = -1;  // -1 for a degenerate face (collapsed to a curve or a point): not a V-surface
  int twin = -1;     // half index of the other side, -1 on the model boundary
  FaceOrientation to_twin;  // this face's (s, t) -> the twin's
  bool degenerate = false;
};

struct VSurface {
  std::array<int, 2> halves{-1, -1};  // halves[1] = -1: boundary V-surface
  std::array<int, 4> curves{};        // V-curves of the face edges of halves[0], in face edge order
  // Shared surfaces only: the two control nets agree after alignment. false = geometrically coincident but
  // differently parametrised or refined (listed in VTopology::non_conforming too).
  bool conforming = true;
  bool boundary() const { return halves[1] < 0; }
};

struct CellEdgeRef {
  int cell = -1, edge = -1;
  bool reversed = false;  // the cell edge runs from VCurve::points[1] to points[0]
};

struct VCurve {
  std::vector<int> surfaces;       // V-surfaces having this curve as an edge, ascending
  std::array<int, 2> points{};     // V-points at the start and the end
  std::vector<CellEdgeRef> cell_edges;
  bool degenerate = false;  // collapsed to a point (length below the gluing tolerance)
};

struct CellCornerRef {
  int cell = -1, corner = -1;
};

struct VPoint {
  std::array<double, 3> position{};
  std::vector<int> curves;  // V-curves starting or ending here, ascending
  std::vector<CellCornerRef> corners;
};

// A pair of cell faces that touch over an area without being a conforming shared face.
struct NonConformingFace {
  enum class Reason {
    control_nets_differ,  // the same surface with different knots, degrees or parametrisation (glued)
    partial_overlap,      // overlapping over part of their area only, e.g. a T-junction (not glued)
  };
  int cell_a = -1, face_a = -1, cell_b = -1, face_b = -1;
  Reason reason = Reason::control_nets_differ;
  std::string describe() const;
};

struct VTopology {
  double tolerance = 0;  // model-space tolerance the gluing used
  std::vector<HalfVSurface> halves;
  std::vector<VSurface> surfaces;
  std::vector<VCurve> curves;
  std::vector<VPoint> points;
  std::vector<std::array<int, 12>> cell_edges;   // V-curve of each cell edge
  std::vector<std::array<int, 8>> cell_corners;  // V-point of each cell corner
  std::vector<NonConformingFace> non_conforming;

  int num_boundary_surfaces() const {
    int n = 0;
    for (const auto& s : surfaces) n += s.boundary() ? 1 : 0;
    return n;
  }
  int num_shared_surfaces() const { return static_cast<int>(surfaces.size()) - num_boundary_surfaces(); }
  // Distinct cells having an edge on the curve (its valence), ascending.
  std::vector<int> cells_around_curve(int curve) const;
};

}  // namespace trivar
