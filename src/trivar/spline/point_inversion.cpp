#include "trivar/spline/point_inversion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <Eigen/Dense>

#include "trivar/core/error.hpp"
#include "trivar/spline/split.hpp"

namespace trivar {

namespace {

template <int D>
struct InversionNode {
  Box<D> domain;
  double diagonal = 0;  // of the model-space bounding box
  int depth = 0;
};

// Per-thread search state; cleared, never shrunk, so repeated queries do not allocate. The nets of the nodes
// on the stack lie in `arena` in stack order, so the top node's net is always the arena's tail.
template <int D>
struct Workspace {
  std::vector<double> arena;
  std::vector<InversionNode<D>> stack;
  std::vector<std::pair<double, int>> candidates;
};

template <int D>
Workspace<D>& workspace() {
  thread_local Workspace<D> ws;
  return ws;
}

// Bounding box of the Cartesian control points of a net in D-space.
template <int D>
Box<D> net_bounds(const double* net, int npts, bool rational) {
  Box<D> b = Box<D>::empty();
  const int st = D + (rational ? 1 : 0);
  double p[D];
  for (int q = 0; q < npts; ++q) {
    const double* c = net + static_cast<std::size_t>(q) * st;
    const double inv = rational ? 1.0 / c[D] : 1.0;
    for (int d = 0; d < D; ++d) p[d] = c[d] * inv;
    b.extend(p);
  }
  return b;
}

// The parametric direction with the longest average control polygon in model space: halving it shrinks the
// bounding box fastest, whatever the element's parametric aspect ratio.
template <int D>
int longest_direction(const double* net, const Ints<D>& degrees, bool rational) {
  const int st = D + (rational ? 1 : 0);
  int npts = 1;
  for (int k = 0; k < D; ++k) npts *= degrees[k] + 1;
  auto point = [&](int q, double* p) {
    const double* c = net + static_cast<std::size_t>(q) * st;
    const double inv = rational ? 1.0 / c[D] : 1.0;
    for (int d = 0; d < D; ++d) p[d] = c[d] * inv;
  };
  int best = 0;
  double best_len = -1;
  for (int k = 0, step = 1; k < D; step *= degrees[k] + 1, ++k) {
    if (degrees[k] == 0) continue;
    double total = 0;
    for (int q = 0; q < npts; ++q) {
      if ((q / step) % (degrees[k] + 1) == degrees[k]) continue;
      double a[D], b[D], s = 0;
      point(q, a);
      point(q + step, b);
      for (int d = 0; d < D; ++d) s += (b[d] - a[d]) * (b[d] - a[d]);
      total += std::sqrt(s);
    }
    const double avg = total * (degrees[k] + 1) / npts;
    if (avg > best_len) best_len = avg, best = k;
  }
  return best;
}

}  // namespace

template <int D>
PointInverter<D>::PointInverter(const TensorSpline<D>& s, InversionOptions opts) : s_(s), opts_(opts) {
  require(s.dim() == D, "point inversion: spline of parametric dimension " + std::to_string(D) +
                            " has control dimension " + std::to_string(s.dim()) + "; they must be equal");
  require(opts.tolerance > 0 && std::isfinite(opts.tolerance),
          "point inversion: tolerance must be positive, got " + std::to_string(opts.tolerance));
  require(opts.max_newton >= 0 && opts.max_depth >= 0, "point inversion: iteration and depth limits must be >= 0");
  elements_ = bezier_elements(s_);
  bounds_.reserve(elements_.size());
  bounds_all_ = Box<D>::empty();
  for (const auto& e : elements_) {
    net_size_ = static_cast<int>(e.coefs.size());
    bounds_.push_back(net_bounds<D>(e.coefs.data(), net_size_ / e.stride(), e.rational));
    bounds_all_.extend(bounds_.back().lo.data());
    bounds_all_.extend(bounds_.back().hi.data());
  }
  const double diag = bounds_all_.diagonal();
  tol_ = opts.tolerance * (diag > 0 ? diag : 1.0);
}

template <int D>
InversionResult<D> PointInverter<D>::newton(const double* x, const Param<D>& guess) const {
  using Vec = Eigen::Matrix<double, D, 1>;
  using Mat = Eigen::Matrix<double, D, D>;
  const Box<D> dom = s_.domain();
  Param<D> u;
  for (int k = 0; k < D; ++k)
    u[k] = std::isfinite(guess[k]) ? std::clamp(guess[k], dom.lo[k], dom.hi[k]) : 0.5 * (dom.lo[k] + dom.hi[k]);
  // Value and first derivatives, then the residual x - s(u).
  double f[(D + 1) * D], ft[(D + 1) * D];
  auto evaluate = [&](const Param<D>& p, double* out, Vec& res) {
    s_.eval_derivs(p, 1, out);
    for (int d = 0; d < D; ++d) res[d] = x[d] - out[d];
    return res.norm();
  };
  Vec res, res_t;
  double rn = evaluate(u, f, res);
  int it = 0;
  while (rn > tol_ && it < opts_.max_newton) {
    ++it;
    Mat J;
    for (int k = 0; k < D; ++k)
      for (int d = 0; d < D; ++d) J(d, k) = f[D * (1 + k) + d];
    // Rank-revealing solve: a degenerate Jacobian (collapsed edge, pole) still gives a usable step.
    const Vec du = J.colPivHouseholderQr().solve(res);
    if (!du.allFinite()) break;
    bool accepted = false;
    double alpha = 1.0;
    for (int h = 0; h < 12 && !accepted; ++h, alpha *= 0.5) {
      Param<D> t;
      bool moved = false;
      for (int k = 0; k < D; ++k) {
        t[k] = std::clamp(u[k] + alpha * du[k], dom.lo[k], dom.hi[k]);
        moved = moved || t[k] != u[k];
      }
      if (!moved) break;  // pushed against the domain boundary: the root is outside
      const double tn = evaluate(t, ft, res_t);
      if (tn < rn) {
        u = t;
        rn = tn;
        res = res_t;
        std::copy(ft, ft + (D + 1) * D, f);
        accepted = true;
      }
    }
    if (!accepted) break;
  }
  InversionResult<D> r;
  r.param = u;
  r.residual = rn;
  r.converged = rn <= tol_;
  r.found = r.converged;
  r.newton_iterations = it;
  return r;
}

template <int D>
InversionResult<D> PointInverter<D>::invert(const double* x) const {
  InversionResult<D> best;
  best.used_fallback = true;
  best.residual = std::numeric_limits<double>::infinity();
  Param<D> xp;
  std::copy(x, x + D, xp.begin());
  if (!bounds_all_.contains(xp, tol_)) {
    best.residual = 0;
    return best;
  }
  const std::size_t ns = static_cast<std::size_t>(net_size_);
  const int npts = net_size_ / s_.stride();
  Workspace<D>& ws = workspace<D>();
  ws.arena.clear();
  ws.stack.clear();
  ws.candidates.clear();
  // Most promising element on top: x nearest its box centre relative to the box size.
  for (std::size_t e = 0; e < elements_.size(); ++e) {
    const Box<D>& b = bounds_[e];
    if (!b.contains(xp, tol_)) continue;
    double d2 = 0;
    for (int k = 0; k < D; ++k) d2 += (xp[k] - 0.5 * (b.lo[k] + b.hi[k])) * (xp[k] - 0.5 * (b.lo[k] + b.hi[k]));
    const double diag = b.diagonal();
    ws.candidates.emplace_back(d2 / (diag * diag + std::numeric_limits<double>::min()), static_cast<int>(e));
  }
  std::sort(ws.candidates.begin(), ws.candidates.end(), std::greater<>());
  for (const auto& [key, e] : ws.candidates) {
    ws.arena.insert(ws.arena.end(), elements_[e].coefs.begin(), elements_[e].coefs.end());
    ws.stack.push_back({elements_[e].domain, bounds_[e].diagonal(), 0});
  }
  const Ints<D> degrees = elements_.empty() ? Ints<D>{} : elements_.front().degrees;
  const bool rational = s_.is_rational();
  bool inside_box = false;  // some node shrank below tolerance (or depth) still containing x
  while (!ws.stack.empty()) {
    const InversionNode<D> n = ws.stack.back();
    ws.stack.pop_back();
    const std::size_t off = ws.arena.size() - ns;
    InversionResult<D> r = newton(x, n.domain.center());
    best.newton_iterations += r.newton_iterations;
    if (r.converged) {
      r.newton_iterations = best.newton_iterations;
      r.used_fallback = true;
      return r;
    }
    if (r.residual < best.residual) {
      best.param = r.param;
      best.residual = r.residual;
    }
    if (n.depth >= opts_.max_depth || n.diagonal <= tol_) {
      inside_box = true;
      ws.arena.resize(off);
      continue;
    }
    const int dir = longest_direction<D>(ws.arena.data() + off, degrees, rational);
    ws.arena.resize(off + 3 * ns);
    double* parent = ws.arena.data() + off;
    double* halves[2] = {parent + ns, parent + 2 * ns};
    split_bezier_net<D>(degrees, s_.stride(), parent, dir, 0.5, halves[0], halves[1]);
    InversionNode<D> child[2] = {n, n};
    const double mid = 0.5 * (n.domain.lo[dir] + n.domain.hi[dir]);
    child[0].domain.hi[dir] = mid;
    child[1].domain.lo[dir] = mid;
    bool keep[2];
    double key[2];
    for (int c = 0; c < 2; ++c) {
      const Box<D> b = net_bounds<D>(halves[c], npts, rational);
      keep[c] = b.contains(xp, tol_);
      child[c].diagonal = b.diagonal();
      child[c].depth = n.depth + 1;
      double d2 = 0;
      for (int k = 0; k < D; ++k) d2 += (xp[k] - 0.5 * (b.lo[k] + b.hi[k])) * (xp[k] - 0.5 * (b.lo[k] + b.hi[k]));
      key[c] = d2 / (child[c].diagonal * child[c].diagonal + std::numeric_limits<double>::min());
    }
    // Push the less promising child first so the better one is searched first.
    const int order[2] = {key[0] >= key[1] ? 0 : 1, key[0] >= key[1] ? 1 : 0};
    std::size_t top = off;
    for (int c : order) {
      if (!keep[c]) continue;
      if (halves[c] != ws.arena.data() + top) std::copy(halves[c], halves[c] + ns, ws.arena.data() + top);
      top += ns;
      ws.stack.push_back(child[c]);
    }
    ws.arena.resize(top);
  }
  best.found = inside_box;
  if (!inside_box) best.residual = 0;
  return best;
}

template <int D>
InversionResult<D> PointInverter<D>::invert(const double* x, const Param<D>& guess) const {
  const InversionResult<D> r = newton(x, guess);
  if (r.converged) return r;
  InversionResult<D> f = invert(x);
  f.newton_iterations += r.newton_iterations;
  return f;
}

template <int D>
InversionResult<D> invert(const TensorSpline<D>& s, const double* x, const InversionOptions& opts) {
  return PointInverter<D>(s, opts).invert(x);
}

template class PointInverter<1>;
template class PointInverter<2>;
template class PointInverter<3>;
template InversionResult<1> invert(const TensorSpline<1>&, const double*, const InversionOptions&);
template InversionResult<2> invert(const TensorSpline<2>&, const double*, const InversionOptions&);
template InversionResult<3> invert(const TensorSpline<3>&, const double*, const InversionOptions&);

}  // namespace trivar
