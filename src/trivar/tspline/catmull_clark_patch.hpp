#pragma once
// The Catmull-Clark limit surface on a quadrilateral face with one extraordinary vertex (a star point of
// valence N != 4) at its corner, evaluated exactly (Stam 1998, "Exact evaluation of Catmull-Clark subdivision
// surfaces at arbitrary parameter values"): the 2N + 8 control points that determine the face are subdivided
// (one linear map per level, built once per valence from the Catmull-Clark rules) until (u, v) falls in one of
// the three regular sub-patches of the level, each a uniform bicubic B-spline; at the star point itself the
// limit position and limit tangents of Halstead et al. 1993 apply. Stam diagonalises the map to jump levels;
// repeated application is the same surface, at O(level * (2N + 8)^2) per point.
//
// Layout of the control points (grid coordinates (a, b) of the regular case N = 4 in brackets): 0 the star
// point (0, 0); 1 + 2i its i-th edge neighbour e_i, 2 + 2i the face neighbour d_i between e_i and e_(i+1),
// counter-clockwise from e_0 (1, 0), d_0 (1, 1), e_1 (0, 1); then 2N + 1 ... 2N + 7 the outer points (2, -1),
// (2, 0), (2, 1), (2, 2), (1, 2), (0, 2), (-1, 2). The face is (star point, e_0, d_0, e_1) with u from the star
// point towards e_0 and v towards e_1.
#include <array>
#include <span>
#include <vector>

namespace trivar {

class CatmullClarkPatch {
public:
  explicit CatmullClarkPatch(int valence);  // 3 <= valence <= 64
  int valence() const { return n_; }
  int size() const { return 2 * n_ + 8; }
  // Value, d/du, d/dv (9 values) at (u, v) in [0, 1]^2. At the star point (0, 0) the derivatives are the limit
  // tangent directions towards e_0 and e_1 (their lengths are not derivatives: the face parametrisation is
  // singular there for N != 4).
  void eval(std::span<const std::array<double, 3>> points, double u, double v, double* out) const;
  // The limit position of the star point.
  std::array<double, 3> limit_point(std::span<const std::array<double, 3>> points) const;

private:
  int n_;
  std::vector<double> subdivide_;            // size() x size(), row-major: the next level's control points
  std::array<std::vector<double>, 3> picks_;  // 16 x size(): the regular sub-patches u >= 1/2 > v, both, v >= 1/2 > u
};

// The patch of one valence, built once (thread-safe).
const CatmullClarkPatch& catmull_clark_patch(int valence);

// The uniform bicubic B-spline patch of a 4 x 4 grid (index (a + 1) + 4 (b + 1), a, b in -1..2) on the cell
// [0, 1]^2 between grid points (0, 0) and (1, 1): value, d/ds, d/dt (9 values).
void eval_uniform_bicubic(std::span<const std::array<double, 3>> grid, double s, double t, double* out);

// The same 4 x 4 grid as the bicubic B-spline on non-uniform knots: the cell [ku[2], ku[3]] x [kv[2], kv[3]] =
// [0, 1]^2 with two knots on either side per direction (ku[2] = 0, ku[3] = 1).
void eval_bicubic_cell(std::span<const std::array<double, 3>> grid, const std::array<double, 6>& ku,
                       const std::array<double, 6>& kv, double s, double t, double* out);

// The 4 x 4 grid of the regular case (valence 4) from the 16 points in the layout above.
std::array<std::array<double, 3>, 16> regular_grid(std::span<const std::array<double, 3>> points);

}  // namespace trivar
