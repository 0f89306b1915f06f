#pragma once
// Non-uniform Catmull-Clark subdivision around one star point (extraordinary vertex of valence N) whose
// neighbourhood is a quadrilateral mesh with knot intervals (the NURCC idea of Sederberg, Zheng, Sewell and Sabin
// 1998: Catmull-Clark rules weighted by knot intervals), and its exact evaluation.
//
// Layout. Sector k is the quadrant between spoke k (its u axis) and spoke k + 1 (its v axis); its points are
// (k, i, j), i >= 1, j >= 0 (j = 0 on spoke k); (k, 0, j) is (k + 1, j, 0) and (0, 0) the star point. Each
// spoke carries knot intervals U_k[0], U_k[1], ... outwards (a quad mesh without T-junctions has one interval
// per strip, so sector k has u intervals U_k and v intervals U_(k+1)).
//
// Rules. Away from the star point they are the tensor product of cubic B-spline knot insertion at the interval
// midpoints, written Catmull-Clark style (p, d, n: the intervals before, of and after an edge on its line):
//   edge curve point  M = ((d + 2n) P + (2p + d) Q) / (2 (p + d + n))
//   face point        the tensor product of the two edge curve rules of the face
//   edge point        (e+ F- + e- F+) / (2 (e- + e+)) + M / 2   (e-, e+: the intervals across of faces F-, F+)
//   vertex point      sum_faces a_s a_t F + sum_spokes a_s M_s / 2 + P / 4, a_s = o_s / (2 (d_s + o_s)) with
//                     d_s the spoke's interval and o_s the opposite spoke's.
// At the star point of valence N the vertex rule is sum (16 / N^2) a_k a_(k+1) F_k + sum (8 / N^2) a_k M_k
// + (1 - sum ...) P, which is Catmull-Clark's (F + 2R + (N - 3) P) / N for equal intervals and the tensor rule
// for N = 4. A line through the star point has no interval beyond it when N != 4: the rules use, for spoke k,
// the mean of the spoke intervals weighted by max(0, -cos(2 pi (m - k) / N)) (the spokes pointing backwards;
// the opposite spoke for N = 4, the two far spokes for N = 3), and for a face at the star point the mean of its
// two rows' values. So: equal intervals give uniform Catmull-Clark, N = 4 gives the bicubic B-spline on those
// knots, and every rule away from the star point's one-ring is exact knot insertion.
//
// Evaluation. Cells of subdivision level j (faces of size 2^-j of the level-0 faces) whose 4 x 4 points and
// 6 + 6 knots avoid the star point are exact bicubic B-spline cells of the level's points and intervals: in
// sector coordinates (x, y) (level-0 faces of size 1) the cells with max(x, y) in [2^(1-j), 2^(2-j)). So a point
// is evaluated by j = 1 + floor(-log2 max(x, y)) subdivision steps of the sector window (5 x 6 points per
// sector) and one B-spline cell; the steps are linear maps built once (three for the first levels, where the
// intervals of the outer strips still enter, then one stationary map). The star point itself is the limit point
// (left eigenvector of the stationary map on the one-ring, eigenvalue 1) and its tangent plane is spanned by the
// two subdominant left eigenvectors.
//
// Continuity: C2 (B-spline) inside every region of exact cells and across the level rings (they share a knot
// grid), so C2 away from the star point; at the star point the surface is continuous with a tangent plane
// common to all sectors (G1 at the point itself) in the limit when the two subdominant eigenvalues are real and
// above the rest. With unequal intervals they differ (Catmull-Clark: equal), and the normals converge slowly
// when they differ much (large interval ratios, high valence): tests/tspline/non_uniform_star_test.cpp measures
// the normals' spread near the point (0 at 1e-8 for valence 3, 0.14 rad for valence 8 at interval ratio 6).
#include <array>
#include <optional>
#include <span>
#include <utility>
#include <vector>

namespace trivar {

// The rules' weights, shared by the star point's sector windows (NonUniformStar) and the global step of a whole
// control mesh (nurcc_step).
// The edge curve point M of an edge of interval d between P and Q (before: the interval beyond P, after: beyond
// Q on the same line): the weights of P and Q.
std::array<double, 2> nurcc_curve_weights(double before, double d, double after);
// The weights of the spokes m of a vertex of valence n that stand for the line beyond it opposite spoke k:
// max(0, -cos(2 pi (m - k) / n)), normalised (valence 4: the opposite spoke alone).
std::vector<double> nurcc_across_weights(int n, int k);
// The interval beyond a vertex opposite its spoke k, from its spokes' intervals (nurcc_across_weights' mean).
double nurcc_across(std::span<const double> spokes, int k);
// The vertex rule's weights at a vertex of valence N = spokes.size(): of the face between spokes k and k + 1
// (faces[k]) and of the edge curve point of spoke k (curves[k]); the vertex itself gets the rest.
struct VertexWeights {
  std::vector<double> faces, curves;
  double self = 1;
};
VertexWeights nurcc_vertex_weights(std::span<const double> spokes);
// The vertex rule of a curve (a crease or the boundary, midpoint knot insertion of its cubic B-spline): the
// weights of the edge curve points before and after the vertex (intervals before, after) and of the vertex,
// V = (after M- + before M+) / (2 (before + after)) + P / 2.
std::array<double, 3> nurcc_curve_vertex_weights(double before, double after);
// The natural end of a cubic at a crease boundary (zero second derivative across it), clamped: the first inner
// control point Q1 = a P0 + b P1 of the clamped cubic on 0, 0, 0, 0, d1, d1 + d2, ... whose end is P0 and whose
// next unclamped point is P1 (crease_ends). Midpoint knot insertion of that curve is the curve rules above with
// the interval beyond P0 taken as d1 (the edge curve point of the first edge is then the clamped curve's).
std::array<double, 2> natural_end_weights(double d1, double d2);

class NonUniformStar {
public:
  static constexpr int kRings = 3;   // level-0 points per sector: 1 <= i <= 3, 0 <= j <= 3
  static constexpr int kWindow = 5;  // points kept per sector and level: 1 <= i <= 5, 0 <= j <= 5
  // intervals[k] = U_k[0..3] along spoke k from the star point (all > 0); 3 <= valence <= 64.
  NonUniformStar(int valence, std::vector<std::array<double, 4>> intervals);
  int valence() const { return n_; }
  // Level-0 points: the star point, then per sector the 12 points (i, j), index 1 + 12 k + 4 (i - 1) + j.
  int size() const { return 1 + n_ * kRings * (kRings + 1); }
  static int index(int sector, int i, int j) { return 1 + 12 * sector + 4 * (i - 1) + j; }
  // Homogeneous value, d/dx, d/dy (12 values) at (x, y) of sector k, 0 <= x, y and max(x, y) <= 2 (the
  // faces (0, 0), (1, 0), (1, 1), (0, 1) of the sector). At the star point the derivatives are two
  // directions spanning the tangent plane, along spoke k and spoke k + 1 in the characteristic map.
  // With `face` (the level-0 face (0, 0), (1, 0), (1, 1) or (0, 1) of the sector the point is taken in), a point
  // on that face's sides is evaluated as the limit from inside it, so its derivatives are the face's own where the
  // knot intervals jump at the side; without, in the cell that holds (x, y), cells half-open upwards.
  void eval(std::span<const std::array<double, 4>> points, int sector, double x, double y, double* out,
            std::optional<std::array<int, 2>> face = std::nullopt) const;
  // The second and third eigenvalues of the stationary map on the one-ring (Catmull-Clark: equal).
  std::array<double, 2> subdominant() const { return lambda_; }

private:
  using Row = std::vector<std::pair<int, double>>;  // sparse weights over the previous level's window
  int n_;
  std::vector<std::array<double, 4>> u_;
  std::array<std::vector<Row>, 4> steps_;  // level 0 -> 1, 1 -> 2, 2 -> 3, then stationary
  std::vector<double> limit_;              // over the one-ring (star, (k, 1, 0), (k, 1, 1)) of level >= 3
  std::array<std::vector<double>, 2> tangent_;
  std::vector<std::array<double, 2>> chart_;  // characteristic map of the one-ring points
  std::array<double, 2> lambda_{};
  std::vector<double> limit0_;                 // the limit point's weights on the level-0 points
  std::array<std::vector<double>, 2> tangent0_;  // the tangent functionals' on the level-0 points

  int window_size() const { return 1 + n_ * kWindow * (kWindow + 1); }
  void build_step(int level, std::vector<Row>& rows) const;
  void build_eigen();
  // One step from `level`: the rows of the points (i, j) with i, j <= radius (of the sectors sector - 1 ..
  // sector + 1 without the star point if sector >= 0).
  void apply(int level, int radius, int sector, const std::vector<std::array<double, 4>>& p,
             std::vector<std::array<double, 4>>& q) const;
  double interval(int level, int spoke, int i) const;  // U at that level, in units of the level's halving
  double across(int spoke) const;
  std::vector<double> first_intervals() const;  // U_k[0] per spoke
};

}  // namespace trivar
