#pragma once
// The Catmull-Clark limit surface with infinitely sharp crease boundaries (Hoppe et al. 1994: crease edge point
// the midpoint, crease vertex (P_prev + 6 P + P_next) / 8 with its two boundary neighbours, corner fixed; smooth
// rules elsewhere) on one face near an irregular vertex of a crease boundary: a crease vertex with other than two
// faces (a crease turning at it, a boundary star point) or a corner with other than one face. Such a vertex has
// no closed-form patch, so the face is evaluated by repeated local subdivision, as Stam's evaluation at star
// points but by applying the rules rather than an eigen-decomposition: at (u, v) the face's two face rings are
// subdivided, kept around the quarter that holds the point, until the point lies in a sub-face whose four
// corners are regular (a smooth vertex of four faces, a crease vertex of two, a corner of one). That sub-face is
// the uniform bicubic B-spline of its 4 x 4 points, with the points missing beyond a crease boundary the natural
// ghosts 2 P0 - P1 (the regular crease patch; at a corner the tensor product of both ends). At an irregular
// corner itself the limit position is the limit mask (crease (P_prev + 4 P + P_next) / 6, corner P, smooth
// (n^2 P + 4 sum E + sum D) / (n (n + 5))), the tangent plane the eigenstructure's where it has one (Eigen's
// EigenSolver). The subdivision levels towards each irregular corner are cached as the 4 x 4 points of their
// regular sub-faces.
// The rules are linear: they act on homogeneous points (w x, w) (rational Catmull-Clark). Hand-written: no
// packaged library evaluates subdivision surfaces with crease boundaries.
#include <array>
#include <optional>
#include <vector>

namespace trivar {

// How subdivision moves a vertex: smooth (interior), crease (on a crease boundary: the curve rule with its two
// boundary neighbours), corner (interpolated).
enum class VertexRule : unsigned char { smooth, crease, corner };

// A net of quadrilaterals round one face: quads[0] is the face (corner 0 at (u, v) = (0, 0), corner 1 at (1, 0),
// counter-clockwise), and the net holds its two face rings (the quads sharing a vertex with a quad that shares a
// vertex with it), so that the vertices of its first ring have all their faces.
struct CreaseNet {
  std::vector<std::array<double, 4>> points;  // homogeneous (w x, w y, w z, w)
  std::vector<VertexRule> rules;
  std::vector<std::array<int, 4>> quads;       // counter-clockwise
  std::vector<std::array<bool, 4>> sharp;      // side k (corner k -> k + 1) on a crease boundary
  // The knot interval of side k (opposite sides equal: one interval per strip); empty: all equal. Kept unhalved
  // by refine (only ratios enter the rules).
  std::vector<std::array<double, 4>> intervals;
};

class CreaseFace {
public:
  // Throws trivar::Error (one line) when the net is not as above (a smooth vertex of the first ring with an open
  // ring of faces, a crease vertex without two crease edges).
  explicit CreaseFace(CreaseNet net);
  bool rational() const { return rational_; }
  // Whether the face's corner c (0..3) is an irregular vertex.
  bool irregular(int c) const { return irregular_[static_cast<std::size_t>(c)]; }
  // Homogeneous value, d/du, d/dv (12 values) at (u, v) in [0, 1]^2. At an irregular corner the value is the
  // limit position (its mask) and the derivatives those 2^-30 from it along the diagonal (the face's
  // parametrisation is singular there), moved into the limit tangent plane where the eigenstructure of the
  // vertex's one-ring subdivision matrix defines one (its two largest eigenvalues below 1, not tied with the next).
  // The crease rules leave the surface without a tangent plane at crease vertices of 4 or more faces (the normals
  // approaching along the boundary and along a diagonal tend to different planes); there the derivatives stay
  // those along the diagonal.
  void eval(double u, double v, double* out) const;

  // A sub-face that is a B-spline cell: its 4 x 4 homogeneous points and its 6 knots per direction (the cell
  // [0, 1], repeated knots where a crease boundary clamps it).
  struct Cell {
    std::array<std::array<double, 4>, 16> points;
    std::array<std::array<double, 6>, 2> knots;
  };

private:
  using Grid = std::array<std::array<double, 4>, 16>;  // a regular sub-face's 4 x 4 homogeneous points
  // Unequal knot intervals: the quadtree of sub-faces down to cells (children by quarter), nets kept where it
  // stops short of an irregular corner (refined on at evaluation).
  struct Node {
    std::optional<Cell> cell;
    std::optional<CreaseNet> net;
    std::array<int, 4> children{-1, -1, -1, -1};
  };
  int build_node(const CreaseNet& net, int level);
  void eval_off_corners(double u, double v, double* out) const;
  CreaseNet net_;
  std::optional<Grid> grid_;   // the face itself when its corners are regular
  std::array<Grid, 4> quarters_;  // the level-1 sub-faces at regular corners
  // Per irregular corner c: chains_[c][l - 1] the net of level l round the sub-face at c, and sides_[c][l - 1][k]
  // its (regular) sub-faces k != c.
  std::array<std::vector<CreaseNet>, 4> chains_;
  std::array<std::vector<std::array<Grid, 4>>, 4> sides_;
  std::array<std::array<double, 12>, 4> corner_values_{};  // eval at the irregular corners
  bool rational_ = false;
  std::array<bool, 4> irregular_{};
  std::vector<Node> tree_;  // unequal intervals: tree_[0] the face
};

// One subdivision step of the net kept round the sub-face of quads[0] at its corner `child` (the new quads[0],
// corner 0 at the parent's (u, v) = (child == 1 || child == 2 ? 1/2 : 0, child >= 2 ? 1/2 : 0), oriented as the
// parent).
CreaseNet refine(const CreaseNet& net, int child);

}  // namespace trivar
