#pragma once
// Star points of odd degree p = 2 m + 1 above 3: the primal quadrilateral subdivision that generalises the uniform
// B-splines of every odd degree (Zorin & Schroeder 2001, "A unified framework for primal/dual quadrilateral
// subdivision schemes"; Stam 2001, "On subdivision schemes generalizing uniform B-spline surfaces of arbitrary
// degree"). One step is linear subdivision (edge midpoints, face centroids) followed by m averaging passes, each
// moving every vertex to the mean of the centroids of its faces. On a regular grid a pass is the tensor mask
// [1 2 1] / 4 per direction, so a step is midpoint knot insertion of the uniform B-spline of degree 2 m + 1: the
// limit surface is that spline wherever the mesh is a regular grid (the T-spline of equal knot intervals), and the
// same rules, applied at any valence, define it at star points. Degree 3 gives a Catmull-Clark variant with other
// weights at star points; trivar keeps Catmull-Clark there (Rhino's and Fusion's rule), so this is for p >= 5.
//
// A face is evaluated as CreaseFace evaluates one: at (u, v) its neighbourhood is subdivided, kept around the
// quarter that holds the point, until the point lies in a sub-face whose block of 2 m + 1 x 2 m + 1 faces round it
// is a grid with four faces at each inner vertex; that sub-face is the uniform B-spline of degree p of the block's
// (p + 1)^2 vertices. (A step's new points of a sub-face's block read the fans of the vertices of its parent's
// block within m - 1 rings of the parent, the parent's inner vertices; by induction every level below is then
// the B-spline's knot insertion.) The levels towards each irregular corner are cached, one net per level round
// the sub-faces not yet regular; at an irregular corner itself the value is the limit of the corner vertex's point
// (refined until its change per level is below 1e-15 of the coordinates' size) and the derivatives are those 2^-30
// from it along the diagonal (the face's parametrisation is singular there). Continuity: C^(p - 1) away from star points; at star
// points tangent-plane continuity is what the eigenstructure of these schemes gives (checked numerically in
// tests/tspline/averaging_face_test.cpp). The rules are linear: they act on homogeneous points (w x, w).
// Hand-written: no packaged library evaluates these schemes.
#include <array>
#include <functional>
#include <optional>
#include <vector>

namespace trivar {

// A net of quadrilaterals round one face: quads[0] is the face (corner 0 at (u, v) = (0, 0), corner 1 at (1, 0),
// counter-clockwise).
struct QuadNet {
  std::vector<std::array<double, 4>> points;  // homogeneous (w x, w y, w z, w)
  std::vector<std::array<int, 4>> quads;
  // Per quad side (side k from corner k to k + 1) the side across, 4 q' + k' (-1: none); empty: found from the quads.
  std::vector<int> twin;
};

// One step of the scheme with `passes` averaging passes, kept within `rings` face rings (faces sharing a vertex with
// the ring before) of the listed sub-faces (4 q + k: quad q's at its corner k, oriented as q), which come first, in
// that order. Throws trivar::Error when a kept vertex's new point reads faces the net does not hold (the net too
// small).
QuadNet averaging_refine(const QuadNet& net, const std::vector<int>& sub_faces, int passes, int rings);

class AveragingFace {
public:
  // The net must hold the face's m + 1 face rings (TMeshSurface gives it the mesh's); degree odd, 3 to 15.
  // Throws trivar::Error (one line) when a vertex the rules read lacks faces.
  AveragingFace(QuadNet net, int degree);
  int degree() const { return degree_; }
  bool rational() const { return rational_; }
  bool irregular(int corner) const { return corner_values_[static_cast<std::size_t>(corner)].has_value(); }
  // Homogeneous value, d/du, d/dv (12 values) at (u, v) in [0, 1]^2.
  void eval(double u, double v, double* out) const;
  // The face tiled by squares [lo, lo + side]^2 of its sub-faces: f(lo, side, corner) with corner -1 for a regular
  // sub-face (one polynomial of degree p: the uniform B-spline patch of its points), else the irregular corner
  // whose square [0, 2^-corner_level]^2 at that corner it is.
  void for_each_square(int corner_level, const std::function<void(const std::array<double, 2>&, double, int)>& f) const;

private:
  using Grid = std::vector<std::array<double, 4>>;  // a regular sub-face's (p + 1)^2 points, u fastest
  struct Node {
    std::optional<Grid> grid;
    int deep = -1;  // below the cached levels: its quad in deep_, refined on at evaluation
    std::array<int, 4> children{-1, -1, -1, -1};
  };
  void eval_grid(const Grid& g, double u, double v, double scale, double* out) const;
  // From quad q of a net of the given level down to a regular sub-face holding (u, v) of q.
  void descend(const QuadNet& start, int q, int level, double u, double v, double scale, double* out) const;
  int degree_, passes_, rings_;
  bool rational_ = false;
  std::vector<Node> tree_;  // tree_[0] the face
  QuadNet deep_;            // the net of the last cached level
  std::array<std::optional<std::array<double, 12>>, 4> corner_values_;
};

}  // namespace trivar
