#include "trivar/model/sweep.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Dense>

#include "trivar/core/error.hpp"
#include "trivar/core/number_format.hpp"
#include "trivar/spline/basis.hpp"

namespace trivar {

namespace {

// Position and unit tangent of the path at u.
void point_tangent(const SplineCurve& path, double u, Eigen::Vector3d& x, Eigen::Vector3d& t) {
  double d[6];
  path.eval_derivs({u}, 1, d);
  x = Eigen::Vector3d(d[0], d[1], d[2]);
  t = Eigen::Vector3d(d[3], d[4], d[5]);
  const double n = t.norm();
  require(n > 0 && std::isfinite(n), [&] { return "sweep: path has a zero tangent at w = " + format_number(u); });
  t /= n;
}

// Knots along the path: its breakpoints with the continuity they have, at degree q, and every element split
// into m equal parts.
KnotVector path_knots(const KnotVector& kv, int q, int sections) {
  const auto bp = kv.breakpoints();
  const int elements = static_cast<int>(bp.size()) - 1;
  const int m = (sections + elements - 1) / elements;
  std::vector<double> t(q + 1, bp.front());
  for (int e = 0; e < elements; ++e) {
    for (int k = 1; k < m; ++k) t.push_back(bp[e] + (bp[e + 1] - bp[e]) * k / m);
    if (e + 1 < elements) t.insert(t.end(), std::min(q, kv.multiplicity(bp[e + 1]) + q - kv.degree()), bp[e + 1]);
  }
  t.insert(t.end(), q + 1, bp.back());
  return KnotVector(q, std::move(t));
}

// The values of all B-splines of kv at u (kv.size() entries).
Eigen::RowVectorXd basis_row(const KnotVector& kv, double u) {
  const int p = kv.degree(), s = kv.find_span(u);
  std::vector<double> N(p + 1);
  basis_values(kv, s, u, N.data());
  Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(kv.size());
  for (int k = 0; k <= p; ++k) row[s - p + k] = N[k];
  return row;
}

}  // namespace

std::vector<Eigen::Matrix3d> rotation_minimizing_frames(const SplineCurve& path, std::span<const double> params,
                                                        double max_step) {
  require(path.dim() == 3, "rotation_minimizing_frames: path must have control dimension 3");
  require(std::isfinite(max_step) && max_step > 0, "rotation_minimizing_frames: step must be positive");
  const auto dom = path.domain();
  double u = dom.lo[0];
  Eigen::Vector3d x, t;
  point_tangent(path, u, x, t);
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(t[k]) < std::abs(t[axis])) axis = k;
  Eigen::Vector3d r = Eigen::Vector3d::Unit(axis) - t[axis] * t;
  r.normalize();

  std::vector<Eigen::Matrix3d> frames;
  frames.reserve(params.size());
  for (const double target : params) {
    require(target >= u && target <= dom.hi[0], [&] {
      return "rotation_minimizing_frames: parameters must be non-decreasing inside the domain, got " +
             format_number(target);
    });
    const int steps = static_cast<int>(std::ceil((target - u) / max_step));
    const double from = u;
    for (int k = 1; k <= steps; ++k) {
      const double next = k == steps ? target : from + (target - from) * k / steps;
      Eigen::Vector3d x1, t1;
      point_tangent(path, next, x1, t1);
      // Reflection in the bisecting plane of x -> x1, then in the plane that maps the reflected tangent to t1.
      const Eigen::Vector3d v1 = x1 - x;
      const double c1 = v1.squaredNorm();
      Eigen::Vector3d rl = r, tl = t;
      if (c1 > 0) {
        rl -= (2 / c1) * v1.dot(r) * v1;
        tl -= (2 / c1) * v1.dot(t) * v1;
      }
      const Eigen::Vector3d v2 = t1 - tl;
      const double c2 = v2.squaredNorm();
      r = c2 > 0 ? Eigen::Vector3d(rl - (2 / c2) * v2.dot(rl) * v2) : rl;
      // Re-orthonormalise: rounding would otherwise accumulate over many steps.
      r = (r - r.dot(t1) * t1).normalized();
      x = x1;
      t = t1;
      u = next;
    }
    Eigen::Matrix3d f;
    f.col(0) = t;
    f.col(1) = r;
    f.col(2) = t.cross(r);
    frames.push_back(f);
  }
  return frames;
}

SweepResult sweep(const SplineSurface& profile, const SplineCurve& path, const SweepOptions& options) {
  require(profile.dim() == 3 && path.dim() == 3, "sweep: profile and path must have control dimension 3");
  require(options.degree >= 1 && options.sections >= 1 && options.samples >= 1 && options.frame_steps >= 1,
          "sweep: degree, sections, samples and frame_steps must be at least 1");
  const int q = std::max(options.degree, path.degree(0));
  const KnotVector kw = path_knots(path.knots(0), q, options.sections);
  const auto bp = kw.breakpoints();
  const std::vector<double> g = kw.greville();
  const int n = kw.size();

  // One frame pass over the Greville abscissae and the error samples together.
  std::vector<double> samples;
  for (std::size_t e = 0; e + 1 < bp.size(); ++e)
    for (int k = 0; k <= options.samples; ++k) samples.push_back(bp[e] + (bp[e + 1] - bp[e]) * k / options.samples);
  std::vector<double> all(g);
  all.insert(all.end(), samples.begin(), samples.end());
  std::sort(all.begin(), all.end());
  const double step = (bp.back() - bp.front()) / (static_cast<double>(bp.size() - 1) * options.frame_steps);
  const auto frames = rotation_minimizing_frames(path, all, step);
  const auto frame_at = [&](double u) { return frames[std::lower_bound(all.begin(), all.end(), u) - all.begin()]; };
  const auto point_at = [&](double u) {
    Eigen::Vector3d x;
    path.eval({u}, x.data());
    return x;
  };
  const Eigen::Vector3d c0 = point_at(bp.front());
  const Eigen::Matrix3d f0t = frame_at(bp.front()).transpose();

  // Right-hand sides: the moved profile's homogeneous coefficients, then C and R themselves (12 columns) so
  // that the fitted motion is available for the error bound.
  const int np = profile.num_coefs(), st = profile.stride();
  Eigen::MatrixXd B(n, n), Y(n, np * st + 12);
  std::vector<Eigen::Matrix3d> rot(n);
  for (int j = 0; j < n; ++j) {
    B.row(j) = basis_row(kw, g[j]);
    const Eigen::Matrix3d R = frame_at(g[j]) * f0t;
    const Eigen::Vector3d c = point_at(g[j]);
    for (int i = 0; i < np; ++i) {
      const double* h = profile.coef(i);
      const double w = profile.weight(i);
      const Eigen::Vector3d moved = R * (Eigen::Vector3d(h[0], h[1], h[2]) - w * c0) + w * c;
      for (int k = 0; k < 3; ++k) Y(j, i * st + k) = moved[k];
      if (st == 4) Y(j, i * st + 3) = w;
    }
    Y.block<1, 3>(j, np * st) = c.transpose();
    for (int k = 0; k < 9; ++k) Y(j, np * st + 3 + k) = R(k % 3, k / 3);
  }
  const Eigen::MatrixXd X = B.partialPivLu().solve(Y);

  std::vector<double> coefs(static_cast<std::size_t>(n) * np * st);
  for (int j = 0; j < n; ++j)
    for (int c = 0; c < np * st; ++c) coefs[static_cast<std::size_t>(j) * np * st + c] = X(j, c);
  SweepResult result;
  result.volume = SplineVolume({profile.knots(0), profile.knots(1), kw}, 3, profile.is_rational(), std::move(coefs));

  std::vector<Eigen::Vector3d> offsets(np);
  for (int i = 0; i < np; ++i) {
    Eigen::Vector3d p;
    profile.control_point(i, p.data());
    offsets[i] = p - c0;
  }
  for (const double u : samples) {
    const Eigen::RowVectorXd fit = basis_row(kw, u) * X.rightCols(12);
    const Eigen::Vector3d dc = fit.head<3>().transpose() - point_at(u);
    Eigen::Matrix3d dr;
    for (int k = 0; k < 9; ++k) dr(k % 3, k / 3) = fit[3 + k];
    dr -= frame_at(u) * f0t;
    for (const auto& o : offsets) result.max_error = std::max(result.max_error, (dc + dr * o).norm());
  }
  return result;
}

}  // namespace trivar
