#include "trivar/model/circle_arc.hpp"

#include <cmath>
#include <numbers>
#include <vector>

#include "trivar/core/error.hpp"
#include "trivar/core/number_format.hpp"

namespace trivar {

SplineCurve circle_arc(const Eigen::Vector3d& center, const Eigen::Vector3d& x_axis, const Eigen::Vector3d& y_axis,
                       double radius, double start_angle, double end_angle) {
  require(std::isfinite(radius) && radius > 0, "circle_arc: radius must be positive, got " + format_number(radius));
  require(center.allFinite() && std::abs(x_axis.norm() - 1) <= 1e-12 && std::abs(y_axis.norm() - 1) <= 1e-12 &&
              std::abs(x_axis.dot(y_axis)) <= 1e-12,
          "circle_arc: the axes must be orthonormal");
  const double sweep = end_angle - start_angle;
  require(std::isfinite(sweep) && sweep != 0 && std::abs(sweep) <= 2 * std::numbers::pi * (1 + 1e-15),
          "circle_arc: the angle swept must be non-zero and at most a full turn, got " + format_number(sweep));
  // One segment per started quarter turn; the slack keeps an exact quarter multiple from starting another.
  const int segments = std::max(1, static_cast<int>(std::ceil(std::abs(sweep) / (0.5 * std::numbers::pi) - 1e-12)));
  const double half = 0.5 * sweep / segments;
  const double w_mid = std::cos(half);

  std::vector<double> knots{0, 0, 0};
  for (int s = 1; s < segments; ++s) knots.insert(knots.end(), 2, static_cast<double>(s) / segments);
  knots.insert(knots.end(), 3, 1.0);

  const auto at = [&](double a, double dist) -> Eigen::Vector3d {
    return center + dist * (std::cos(a) * x_axis + std::sin(a) * y_axis);
  };
  std::vector<double> h;
  for (int j = 0; j <= 2 * segments; ++j) {
    const double a = start_angle + j * half;
    // Odd controls: the tangents' intersection, at distance radius / cos(half) on the bisector.
    const double w = j % 2 ? w_mid : 1.0;
    const Eigen::Vector3d p = at(a, j % 2 ? radius / w_mid : radius);
    for (int k = 0; k < 3; ++k) h.push_back(w * p[k]);
    h.push_back(w);
  }
  return SplineCurve({KnotVector(2, std::move(knots))}, 3, true, std::move(h));
}

std::array<SplineSurface, 5> disk_cells(double radius, double core) {
  require(std::isfinite(radius) && radius > 0, "disk_cells: radius must be positive, got " + format_number(radius));
  require(std::isfinite(core) && core > 0 && core < 1,
          "disk_cells: core fraction must lie in (0, 1), got " + format_number(core));
  const double h = std::sqrt(0.5);  // cos 45 deg = sin 45 deg, one value for both so the cells stay symmetric
  const double s = core * radius * h;
  const KnotVector quad(2, {0, 0, 0, 1, 1, 1}), lin(1, {0, 0, 1, 1});

  std::vector<double> square;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) square.insert(square.end(), {(i - 1) * s, (j - 1) * s, 0.0, 1.0});

  // +x cell: the side runs from (s, s) down to (s, -s) and the arc from 45 to -45 degrees, which makes
  // (u, v) = (-y, +x) locally, a positive frame. The arc's middle control point (radius sqrt 2, 0) has
  // weight h, so its homogeneous x is exactly radius.
  const std::vector<double> east{s, s, 0, 1, s, 0, 0, 1, s, -s, 0, 1,
                                 radius * h, radius * h, 0, 1, radius, 0, 0, h, radius * h, -radius * h, 0, 1};
  std::array<SplineSurface, 5> cells;
  cells[0] = SplineSurface({quad, quad}, 3, true, std::move(square));
  std::vector<double> c = east;
  for (int q = 1; q <= 4; ++q) {
    cells[q] = SplineSurface({quad, lin}, 3, true, c);
    for (std::size_t i = 0; i < c.size(); i += 4) {  // quarter turn (x, y) -> (-y, x) for the next cell
      const double x = c[i];
      c[i] = -c[i + 1];
      c[i + 1] = x;
    }
  }
  return cells;
}

}  // namespace trivar
