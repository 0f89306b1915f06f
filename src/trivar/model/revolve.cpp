#include "trivar/model/revolve.hpp"

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "trivar/core/error.hpp"
#include "trivar/core/number_format.hpp"

namespace trivar {

namespace {

// Number of rational quadratic arcs: one per started quarter turn. The slack keeps exact quarter multiples
// (pi/2, pi, 2 pi computed in floating point) from starting a needless extra segment.
int arc_segments(double angle) {
  const double quarters = angle / (0.5 * std::numbers::pi);
  return std::max(1, static_cast<int>(std::ceil(quarters - 1e-12)));
}

// (cos a, sin a), exact at multiples of a quarter turn: std::cos(pi / 2) is 6e-17, which would put the control
// points of quarter, half and full turns off the axes they belong on.
Eigen::Vector2d cos_sin(double a) {
  constexpr double quarter = 0.5 * std::numbers::pi;
  const double q = std::round(a / quarter);
  double r = a - q * quarter;
  if (std::abs(r) < 1e-14) r = 0;  // rounding of the angle, not a real offset
  const double c = std::cos(r), s = std::sin(r);
  switch (static_cast<int>(q) & 3) {
    case 0: return {c, s};
    case 1: return {-s, c};
    case 2: return {-c, -s};
    default: return {s, -c};
  }
}

}  // namespace

template <int D>
TensorSpline<D> revolve(const TensorSpline<D - 1>& profile, const Eigen::Vector3d& axis_point,
                        const Eigen::Vector3d& axis_dir, double angle_radians) {
  static_assert(D == 2 || D == 3, "revolve makes surfaces from curves and volumes from surfaces");
  require(profile.dim() == 3, "revolve: profile must have control dimension 3, got " + std::to_string(profile.dim()));
  require(axis_point.allFinite() && axis_dir.allFinite() && axis_dir.norm() > 0,
          "revolve: axis direction must be finite and non-zero");
  require(std::isfinite(angle_radians) && angle_radians > 0 && angle_radians <= 2 * std::numbers::pi,
          "revolve: angle must be in (0, 2 pi] radians, got " + format_number(angle_radians));

  const Eigen::Vector3d d = axis_dir.normalized();
  const int segments = arc_segments(angle_radians);

  std::vector<double> knots{0, 0, 0};
  for (int s = 1; s < segments; ++s) knots.insert(knots.end(), 2, static_cast<double>(s) / segments);
  knots.insert(knots.end(), 3, 1.0);

  std::array<KnotVector, D> kv;
  for (int k = 0; k + 1 < D; ++k) kv[k] = profile.knots(k);
  kv[D - 1] = KnotVector(2, std::move(knots));

  // Even angular controls j lie on the circle at angle (j / 2) * segment. Odd ones are the tangent
  // intersections, (P_{j-1} + P_{j+1}) / (1 + cos(segment)) about the axis, weighted cos(segment / 2), which
  // makes each arc exactly circular; this form keeps quarter-turn intersections exact.
  const int n_angular = 2 * segments + 1;
  const double segment = angle_radians / segments;
  const double to_corner = 1.0 / (1.0 + cos_sin(segment)[0]);
  std::vector<Eigen::Vector2d> rot(n_angular);  // coefficients of (radial, normal)
  std::vector<double> weight(n_angular);
  for (int j = 0; j < n_angular; j += 2) rot[j] = cos_sin((j / 2) * segment);
  for (int j = 1; j < n_angular; j += 2) rot[j] = to_corner * (rot[j - 1] + rot[j + 1]);
  for (int j = 0; j < n_angular; ++j) weight[j] = j % 2 ? std::cos(0.5 * segment) : 1.0;

  // The profile's grid is the fast part of the result's grid (angular direction last), so every angular
  // index is one contiguous copy of the rotated profile.
  const int n_profile = profile.num_coefs();
  std::vector<double> h(static_cast<std::size_t>(n_profile) * n_angular * 4);
  for (int i = 0; i < n_profile; ++i) {
    Eigen::Vector3d x;
    profile.control_point(i, x.data());
    const double w = profile.weight(i);
    const Eigen::Vector3d foot = axis_point + (x - axis_point).dot(d) * d;
    const Eigen::Vector3d radial = x - foot;
    const Eigen::Vector3d normal = d.cross(radial);
    for (int j = 0; j < n_angular; ++j) {
      const Eigen::Vector3d p = foot + rot[j][0] * radial + rot[j][1] * normal;
      const double wj = w * weight[j];
      double* c = h.data() + (static_cast<std::size_t>(j) * n_profile + i) * 4;
      for (int k = 0; k < 3; ++k) c[k] = wj * p[k];
      c[3] = wj;
    }
  }
  return TensorSpline<D>(std::move(kv), 3, true, std::move(h));
}

template TensorSpline<2> revolve<2>(const TensorSpline<1>&, const Eigen::Vector3d&, const Eigen::Vector3d&, double);
template TensorSpline<3> revolve<3>(const TensorSpline<2>&, const Eigen::Vector3d&, const Eigen::Vector3d&, double);

}  // namespace trivar
