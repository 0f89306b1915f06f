#pragma once
// The Catmull-Clark limit surface with infinitely sharp crease boundaries (Hoppe et al. 1994: crease edge point
// the midpoint, crease vertex (P_prev + 6 P + P_next) / 8 with its two boundary neighbours, corner fixed; smooth
// rules elsewhere) on one face near an irregular vertex of a crease boundary: a crease vertex with other than two
// faces (a crease turning at it, a boundary star point), a corner with other than one face (a cone point: a
// corner inside the mesh), or a dart (the end of a crease inside the mesh, cut open up to it: the smooth rule over
// its fan of faces, the slit's two sides one edge whose edge points are midpoints). Such a vertex has
// no closed-form patch, so the face is evaluated by repeated local subdivision, as Stam's evaluation at star
// points but by applying the rules rather than an eigen-decomposition: at (u, v) the face's two face rings are
// subdivided, kept around the quarter that holds the point, until the point lies in a sub-face whose four
// corners are regular (a smooth vertex of four faces, a crease vertex of two, a corner of one). That sub-face is
// the uniform bicubic B-spline of its 4 x 4 points, with the points missing beyond a crease boundary the natural
// ghosts 2 P0 - P1 (the regular crease patch; at a corner the tensor product of both ends). At an irregular
// corner itself the limit position is the limit mask (crease (P_prev + 4 P + P_next) / 6, corner P, smooth
// (n^2 P + 4 sum E + sum D) / (n (n + 5)); a dart's from the left eigenvector of eigenvalue 1 of its one-ring
// subdivision matrix, as the slit's midpoint rule moves it off the smooth mask), the tangent plane the
// eigenstructure's where it has one (Eigen's EigenSolver; none at a cone point). The subdivision levels towards
// each irregular corner are cached as the 4 x 4 points of their regular sub-faces.
// Unequal knot intervals (one per strip of quads; CreaseNet::intervals) take the non-uniform rules of NURCC
// (Sederberg et al. 1998; the weight functions of non_uniform_catmull_clark, each interval beyond an edge's end
// read along its line), midpoint knot insertion of the bicubic B-spline wherever the neighbourhood is regular. At
// a crease boundary the surface is crease_ends' natural end: across the boundary the clamped cubic of Q0 = P0,
// Q1 = ((d1 + d2) P0 + d1 P1) / (2 d1 + d2), Q2 = P1, ...; inserting the midpoints of its intervals keeps Q0 = P0
// (the boundary row refines along the boundary alone: crease vertex V = (b M- + a M+) / (2 (a + b)) + P / 2 with
// a, b its crease edges' intervals and M the edge curve points, crease edge point M), gives the first cross edge's
// curve point f(0, d1 / 2, d1) = ((d1 + 2 d2) Q1 + d1 P1) / (2 (d1 + d2)), which is NURCC's curve rule with the
// interval beyond P0 taken as d1 (the edge's own), and leaves every other rule NURCC's; the new Q1 keeps the
// relation (the same surface), so the rules hold on every level. So: where an edge's line ends at a crease
// boundary (an edge across it at its crease vertex, any edge at a corner) the interval beyond is the edge's own;
// a crease continues along its two crease edges. At an irregular vertex the same local rules are taken: the
// crease curve's rule along its two crease edges (so the crease is the non-uniform cubic B-spline of its vertices
// on their intervals), the natural end for the edges into the mesh whatever the number of faces (it depends on
// the edge alone, as at a regular crease vertex), corners fixed, and at an interior star point NURCC's star rule
// (nurcc_vertex_weights, nurcc_across): equal intervals give the uniform crease rules, two faces the knot
// insertion above. A sub-face is then a B-spline cell of its 4 x 4 points on their knots (clamped, Q1 as above,
// where a crease boundary ends its lines) when all 16 points are regular vertices: next to an irregular vertex
// the rules are no knot insertion (as next to NonUniformStar's star point), so faces there are subdivided one
// level further than with equal intervals. At a dart NURCC's smooth rule runs over its fan from one side of the
// slit to the other (the closed fan before the cut). The limit point and tangent plane at an
// irregular corner come from the eigenvectors of its one ring's subdivision matrix, read off the rules themselves
// at level 3 (stationary from there). Measured (tests/tspline/crease_face_test.cpp): knot insertion of the exact
// surface (grids with intervals 1 : 1.02, 1.5, 3, polynomial and rational) to 7e-15 in value and 9e-14 in
// relative derivatives; an
// interior star point equals NonUniformStar to 2e-15 (derivatives 6e-13); round crease vertices of 3 and 4 faces
// and on the creased box C0 to 4e-15, normals and C1 (per knot unit) across every edge to 4e-14, the crease the
// de Boor B-spline to 1.3e-15; the normals 2^-30 from a crease vertex of 3 faces within 3e-6 rad of one another
// and of the eigenvectors' plane at the vertex (1e-3 at 2^-10: slow as at NonUniformStar, the subdominant
// eigenvalues differ), with 4 faces no tangent plane (as with equal intervals).
// The rules are linear: they act on homogeneous points (w x, w) (rational Catmull-Clark). Hand-written: no
// packaged library evaluates subdivision surfaces with crease boundaries.
#include <array>
#include <functional>
#include <optional>
#include <vector>

namespace trivar {

// How subdivision moves a vertex: smooth (interior), crease (on a crease boundary: the curve rule with its two
// boundary neighbours), corner (interpolated), dart (the end of a slit, one crease boundary through it: the smooth
// rule over its fan of faces, the slit's two sides counted as one edge).
enum class VertexRule : unsigned char { smooth, crease, corner, dart };

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
  // Whether the face has unequal knot intervals nearby: then it is a quadtree of B-spline cells (for_each_cell).
  bool has_cells() const { return !tree_.empty(); }
  // Unequal intervals: the B-spline cells tiling the face but for the squares [0, 2^-corner_level]^2 at its
  // irregular corners (their sub-faces near the corner are never cells), refined on past the cached levels:
  // f(cell, lo, side) with the cell's square [lo, lo + side]^2 of the face. Each cell is one bicubic polynomial on
  // its square, so a patch exporter converts it exactly.
  void for_each_cell(int corner_level, const std::function<void(const Cell&, const std::array<double, 2>&, double)>& f) const;

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
  // Per irregular corner c: chains_[c][l - 1] the net of level l round the sub-face at c (l = 1 .. the cached
  // levels + 1, the last where evaluation subdivides on), and sides_[c][l - 1][k] its (regular) sub-faces k != c.
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

// Homogeneous value, d/du, d/dv (12 values) of a cell at (u, v) in its [0, 1]^2, the derivatives times `scale`
// (1 / the side of the cell's square in the coordinates they are wanted in).
void eval_cell(const CreaseFace::Cell& c, double u, double v, double scale, double* out);

}  // namespace trivar
