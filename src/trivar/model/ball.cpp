#include "trivar/model/ball.hpp"

#include <cmath>
#include <cstdlib>

#include "trivar/core/error.hpp"
#include "trivar/core/number_format.hpp"
#include "trivar/model/ruled.hpp"
#include "trivar/spline/affine_transform.hpp"

namespace trivar {

namespace {

KnotVector bezier_knots(int p) {
  std::vector<double> t(p + 1, 0.0);
  t.insert(t.end(), p + 1, 1.0);
  return KnotVector(p, std::move(t));
}

}  // namespace

SplineSurface cube_sphere_patch(double radius) {
  require(std::isfinite(radius) && radius > 0,
          "cube_sphere_patch: radius must be positive, got " + format_number(radius));
  const double r2 = std::sqrt(2.0), r3 = std::sqrt(3.0), r6 = std::sqrt(6.0);
  // Cobb's net has the symmetry of the square, so it is listed by distance from the centre index:
  // a = |i - 2|, b = |j - 2|. W and Z (homogeneous z) are symmetric in (a, b); X is the homogeneous |x|,
  // zero on the middle row, and y follows from x by the diagonal symmetry.
  const double W[3][3] = {{4 * (5 * r3 - 1) / 9, r2 * (r3 + 6) / 3, 4 * (5 - r3) / 3},
                          {r2 * (r3 + 6) / 3, (r3 + 6) / 2, r2 * (3 * r3 - 2)},
                          {4 * (5 - r3) / 3, r2 * (3 * r3 - 2), 4 * (3 - r3)}};
  const double Z[3][3] = {{4 * (5 - r3) / 3, 5 * r6 / 3, 4 * (2 * r3 - 1) / 3},
                          {5 * r6 / 3, (r3 + 6) / 2, r2 * (4 - r3)},
                          {4 * (2 * r3 - 1) / 3, r2 * (4 - r3), 4 * (r3 - 1)}};
  const double X[3][3] = {{0, 0, 0},
                          {r2 * (7 - 2 * r3) / 3, (3 * r3 - 2) / 2, r2},
                          {4 * (2 * r3 - 1) / 3, r2 * (4 - r3), 4 * (r3 - 1)}};
  const auto sign = [](int k) { return k < 2 ? -1.0 : 1.0; };
  std::vector<double> h;
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 5; ++i) {
      const int a = std::abs(i - 2), b = std::abs(j - 2);
      h.insert(h.end(), {radius * sign(i) * X[a][b], radius * sign(j) * X[b][a], radius * Z[a][b], W[a][b]});
    }
  return SplineSurface({bezier_knots(4), bezier_knots(4)}, 3, true, std::move(h));
}

CellComplex make_ball(const BallSpec& spec) {
  require(std::isfinite(spec.radius) && spec.radius > 0,
          "make_ball: radius must be positive, got " + format_number(spec.radius));
  require(spec.center.allFinite(), "make_ball: center must be finite");
  require(std::isfinite(spec.core) && spec.core > 0 && spec.core < 1,
          "make_ball: core fraction must lie in (0, 1), got " + format_number(spec.core));
  const double a = spec.core * spec.radius / std::sqrt(3.0);
  const auto grid = [a](int i) { return a * (i - 2) / 2; };  // the flat face or cube, degree 4, uniform

  std::vector<double> face, cube;
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 5; ++i) face.insert(face.end(), {grid(i), grid(j), a, 1.0});
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 5; ++i) cube.insert(cube.end(), {grid(i), grid(j), grid(k), 1.0});
  const KnotVector b4 = bezier_knots(4);
  const SplineSurface flat({b4, b4}, 3, true, std::move(face));
  const SplineVolume top = ruled<3>(flat, cube_sphere_patch(spec.radius));

  // Proper rotations (row-major) taking +z to +x, -x, +y, -y, +z, -z.
  const double rot[6][9] = {{0, 0, 1, 0, 1, 0, -1, 0, 0},  {0, 0, -1, 0, 1, 0, 1, 0, 0},
                            {1, 0, 0, 0, 0, 1, 0, -1, 0},  {1, 0, 0, 0, 0, -1, 0, 1, 0},
                            {1, 0, 0, 0, 1, 0, 0, 0, 1},   {1, 0, 0, 0, -1, 0, 0, 0, -1}};
  CellComplex cells;
  cells.push_back(transform(SplineVolume({b4, b4, b4}, 3, true, std::move(cube)), Eigen::Matrix3d::Identity(),
                            spec.center));
  for (const auto& r : rot) {
    const Eigen::Matrix3d R = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(r);
    cells.push_back(transform(top, R, spec.center));
  }
  return cells;
}

}  // namespace trivar
