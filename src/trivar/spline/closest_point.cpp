#include "trivar/spline/closest_point.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <string>

#include <Eigen/Dense>

#include "trivar/core/error.hpp"
#include "trivar/spline/bezier_extraction.hpp"
#include "trivar/spline/derivative_index.hpp"
#include "trivar/spline/split.hpp"

namespace trivar {

namespace {

// Branch and bound stops refining nodes whose bound is within this gap (relative to the model size) of the
// best distance; Newton, not the bound, supplies the final accuracy.
constexpr double kPruneGap = 1e-7;
// Safeguards for degenerate inputs where a continuum of points is equally close (x at a sphere's centre).
constexpr int kMaxDepth = 60;
constexpr int kMaxNodes = 20000;
constexpr int kMaxNewton = 50;

template <int D>
struct Node {
  double bound = 0;
  Box<D> domain;
  int depth = 0;
  std::vector<double> net;
  bool operator>(const Node& o) const { return bound > o.bound; }
};

// Lower bound on the distance from x to the convex hull of a net: distance from x to the net's bounding box in
// an orthonormal frame whose first axes span the net's average tangent directions.
template <int D>
double hull_distance_bound(const std::vector<double>& net, const Ints<D>& degrees, int dim, bool rational,
                           const double* x) {
  const int st = dim + (rational ? 1 : 0);
  const int npts = static_cast<int>(net.size()) / st;
  Eigen::MatrixXd P(dim, npts);
  for (int q = 0; q < npts; ++q) {
    const double* c = net.data() + static_cast<std::size_t>(q) * st;
    const double inv = rational ? 1.0 / c[dim] : 1.0;
    for (int d = 0; d < dim; ++d) P(d, q) = c[d] * inv - x[d];
  }
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(dim, D);
  for (int k = 0, step = 1; k < D; step *= degrees[k] + 1, ++k)
    for (int q = 0; q < npts; ++q)
      if ((q / step) % (degrees[k] + 1) != degrees[k]) T.col(k) += P.col(q + step) - P.col(q);
  const Eigen::MatrixXd Q = Eigen::HouseholderQR<Eigen::MatrixXd>(T).householderQ();
  const Eigen::MatrixXd Y = Q.transpose() * P;
  double d2 = 0;
  for (int a = 0; a < dim; ++a) {
    const double lo = Y.row(a).minCoeff(), hi = Y.row(a).maxCoeff();
    const double g = lo > 0 ? lo : (hi < 0 ? -hi : 0.0);
    d2 += g * g;
  }
  return std::sqrt(d2);
}

// The parametric direction with the longest average control polygon in model space: halving it shrinks the
// node fastest, also next to a degenerate edge or pole where one direction has no extent at all.
template <int D>
int longest_direction(const std::vector<double>& net, const Ints<D>& degrees, int dim, bool rational) {
  const int st = dim + (rational ? 1 : 0);
  const int npts = static_cast<int>(net.size()) / st;
  auto coord = [&](int q, int d) {
    const double* c = net.data() + static_cast<std::size_t>(q) * st;
    return rational ? c[d] / c[dim] : c[d];
  };
  int best = 0;
  double best_len = -1;
  for (int k = 0, step = 1; k < D; step *= degrees[k] + 1, ++k) {
    if (degrees[k] == 0) continue;
    double total = 0;
    for (int q = 0; q < npts; ++q) {
      if ((q / step) % (degrees[k] + 1) == degrees[k]) continue;
      double s2 = 0;
      for (int d = 0; d < dim; ++d) s2 += (coord(q + step, d) - coord(q, d)) * (coord(q + step, d) - coord(q, d));
      total += std::sqrt(s2);
    }
    const double avg = total * (degrees[k] + 1) / npts;
    if (avg > best_len) best_len = avg, best = k;
  }
  return best;
}

template <int D>
struct Local {
  Param<D> u{};
  double distance = std::numeric_limits<double>::infinity();
  bool converged = false;
};

// Bound-constrained Newton on phi(u) = |s(u) - x|^2 / 2 (projected Newton with an active set and a
// backtracking line search; Gauss-Newton when the Hessian is not positive definite).
template <int D>
Local<D> minimize_distance(const TensorSpline<D>& s, const double* x, Param<D> u, double tol, double* F,
                           double* pt) {
  using Vec = Eigen::Matrix<double, D, 1>;
  using Mat = Eigen::Matrix<double, D, D>;
  const int dim = s.dim();
  const Box<D> dom = s.domain();
  int second[D][D];
  for (int k = 0; k < D; ++k)
    for (int l = 0; l < D; ++l) {
      std::array<int, D> a{};
      ++a[k];
      ++a[l];
      second[k][l] = derivative_position<D>(a);
    }
  auto phi_at = [&](const Param<D>& p) {
    s.eval(p, pt);
    double v = 0;
    for (int d = 0; d < dim; ++d) v += (pt[d] - x[d]) * (pt[d] - x[d]);
    return 0.5 * v;
  };
  Local<D> out;
  double phi = 0;
  for (int it = 0; it <= kMaxNewton; ++it) {
    s.eval_derivs(u, 2, F);
    const double* r0 = F;
    Vec g;
    Mat H, G;
    double speed[D];
    phi = 0;
    for (int d = 0; d < dim; ++d) phi += 0.5 * (r0[d] - x[d]) * (r0[d] - x[d]);
    for (int k = 0; k < D; ++k) {
      const double* fk = F + static_cast<std::size_t>(1 + k) * dim;
      double gk = 0, sk = 0;
      for (int d = 0; d < dim; ++d) {
        gk += (r0[d] - x[d]) * fk[d];
        sk += fk[d] * fk[d];
      }
      g[k] = gk;
      speed[k] = std::sqrt(sk);
      for (int l = 0; l < D; ++l) {
        const double* fl = F + static_cast<std::size_t>(1 + l) * dim;
        const double* fkl = F + static_cast<std::size_t>(second[k][l]) * dim;
        double jj = 0, rh = 0;
        for (int d = 0; d < dim; ++d) {
          jj += fk[d] * fl[d];
          rh += (r0[d] - x[d]) * fkl[d];
        }
        G(k, l) = jj;
        H(k, l) = jj + rh;
      }
    }
    // Active set: at a bound with the descent direction pointing out of the domain. The gradient carries a
    // rounding error of about eps |r| |s_u|, which matters where a tangent degenerates (a pole).
    const double max_speed = *std::max_element(speed, speed + D);
    const double floor = 64 * std::numeric_limits<double>::epsilon() * std::sqrt(2 * phi) * max_speed;
    bool converged = true;
    for (int k = 0; k < D; ++k) {
      const bool fixed = (u[k] <= dom.lo[k] && g[k] > 0) || (u[k] >= dom.hi[k] && g[k] < 0);
      if (fixed) {
        g[k] = 0;
        H.row(k).setZero();
        H.col(k).setZero();
        G.row(k).setZero();
        G.col(k).setZero();
        H(k, k) = G(k, k) = 1;
      } else if (std::abs(g[k]) > tol * speed[k] + floor) {
        converged = false;
      }
    }
    out.converged = converged;
    if (converged || it == kMaxNewton) break;
    Vec step;
    const Eigen::LDLT<Mat> ldlt(H);
    bool newton_ok = ldlt.info() == Eigen::Success && (ldlt.vectorD().array() > 0).all();
    if (newton_ok) {
      step = -ldlt.solve(g);
      newton_ok = step.allFinite() && step.dot(g) < 0;
    }
    if (!newton_ok) {
      // Gauss-Newton is a descent direction whenever J has full rank; the tiny shift covers rank loss.
      G.diagonal().array() += 1e-14 * (G.diagonal().maxCoeff() + 1e-300);
      step = -G.ldlt().solve(g);
      if (!step.allFinite()) break;
    }
    // Predicted model-space movement below tolerance: this step is the last one.
    double move2 = 0;
    for (int d = 0; d < dim; ++d) {
      double m = 0;
      for (int k = 0; k < D; ++k)
        m += F[static_cast<std::size_t>(1 + k) * dim + d] * (std::clamp(u[k] + step[k], dom.lo[k], dom.hi[k]) - u[k]);
      move2 += m * m;
    }
    const bool last = std::sqrt(move2) <= tol;
    // Near the minimum phi changes by less than its rounding error; a step that does not increase phi beyond
    // that noise is accepted, otherwise Newton would stop at a tangential residual of about sqrt(eps).
    // phi is compared through one evaluation path (eval), whose rounding is about eps |r| |s|.
    const double phi0 = phi_at(u);
    double size = 0;
    for (int d = 0; d < dim; ++d) size = std::max(size, std::abs(pt[d]));
    const double noise = 16 * std::numeric_limits<double>::epsilon() * (phi0 + std::sqrt(2 * phi0) * size);
    bool accepted = false;
    double alpha = 1.0;
    for (int h = 0; h < 30 && !accepted; ++h, alpha *= 0.5) {
      Param<D> t;
      bool moved = false;
      for (int k = 0; k < D; ++k) {
        t[k] = std::clamp(u[k] + alpha * step[k], dom.lo[k], dom.hi[k]);
        moved = moved || t[k] != u[k];
      }
      if (!moved) break;
      const double phi_t = phi_at(t);
      if (phi_t < phi0 || (phi_t <= phi0 + noise && h == 0)) {
        u = t;
        accepted = true;
      }
    }
    if (last) {
      out.converged = true;
      break;
    }
    if (!accepted) break;
  }
  out.u = u;
  out.distance = std::sqrt(2 * phi);
  return out;
}

}  // namespace

template <int D>
ClosestPoint<D> closest_point(const TensorSpline<D>& s, const double* x, double tolerance) {
  require(tolerance > 0 && std::isfinite(tolerance),
          "closest point: tolerance must be positive, got " + std::to_string(tolerance));
  const int dim = s.dim();
  std::vector<double> lo(dim), hi(dim);
  s.control_bounds(lo.data(), hi.data());
  double diag = 0;
  for (int d = 0; d < dim; ++d) diag += (hi[d] - lo[d]) * (hi[d] - lo[d]);
  const double scale = diag > 0 ? std::sqrt(diag) : 1.0;
  const double tol = tolerance * scale, gap = kPruneGap * scale;

  std::vector<double> F(static_cast<std::size_t>(derivative_count(D, 2)) * dim), pt(dim);
  Local<D> best;
  std::priority_queue<Node<D>, std::vector<Node<D>>, std::greater<>> heap;
  auto elements = bezier_elements(s);
  const Ints<D> degrees = elements.front().degrees;
  for (auto& e : elements) {
    Node<D> n;
    n.bound = hull_distance_bound<D>(e.coefs, degrees, dim, s.is_rational(), x);
    n.domain = e.domain;
    n.net = std::move(e.coefs);
    heap.push(std::move(n));
  }
  for (int visited = 0; !heap.empty() && visited < kMaxNodes; ++visited) {
    Node<D> n = heap.top();
    heap.pop();
    if (n.bound >= best.distance - gap) break;  // every remaining node is at least as far
    const Param<D> c = n.domain.center();
    s.eval(c, pt.data());
    double dc = 0;
    for (int d = 0; d < dim; ++d) dc += (pt[d] - x[d]) * (pt[d] - x[d]);
    if (n.depth == 0 || std::sqrt(dc) < best.distance) {
      const Local<D> l = minimize_distance<D>(s, x, c, tol, F.data(), pt.data());
      // Within tolerance, two results are the same minimum reached from different starts; prefer a converged one.
      const bool better = l.converged && !best.converged ? l.distance <= best.distance + tol
                                                         : l.distance < best.distance - (best.converged ? tol : 0.0);
      if (better) best = l;
    }
    if (n.depth >= kMaxDepth) continue;
    const int dir = longest_direction<D>(n.net, degrees, dim, s.is_rational());
    Node<D> child[2];
    const double mid = 0.5 * (n.domain.lo[dir] + n.domain.hi[dir]);
    for (int h = 0; h < 2; ++h) {
      child[h].domain = n.domain;
      child[h].depth = n.depth + 1;
      child[h].net.resize(n.net.size());
    }
    child[0].domain.hi[dir] = mid;
    child[1].domain.lo[dir] = mid;
    split_bezier_net<D>(degrees, s.stride(), n.net.data(), dir, 0.5, child[0].net.data(), child[1].net.data());
    for (auto& ch : child) {
      ch.bound = hull_distance_bound<D>(ch.net, degrees, dim, s.is_rational(), x);
      if (ch.bound < best.distance - gap) heap.push(std::move(ch));
    }
  }
  ClosestPoint<D> out;
  out.param = best.u;
  out.point.resize(dim);
  s.eval(best.u, out.point.data());
  double d2 = 0;
  for (int d = 0; d < dim; ++d) d2 += (out.point[d] - x[d]) * (out.point[d] - x[d]);
  out.distance = std::sqrt(d2);
  out.converged = best.converged;
  return out;
}

template ClosestPoint<1> closest_point(const TensorSpline<1>&, const double*, double);
template ClosestPoint<2> closest_point(const TensorSpline<2>&, const double*, double);
template ClosestPoint<3> closest_point(const TensorSpline<3>&, const double*, double);

}  // namespace trivar
