#include "trivar/iga/conforming_split.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <string>

#include "trivar/core/error.hpp"
#include "trivar/spline/split.hpp"

namespace trivar {

namespace {

using XY = std::array<double, 3>;  // a point of a patch (z = 0 for planar ones)

XY corner_at(const TensorSpline<2>& s, double u, double v) {
  XY x{};
  s.eval({u, v}, x.data());
  return x;
}

double point_distance(const double* y, const XY& x, int dim) {
  double d = 0;
  for (int c = 0; c < dim; ++c) d += (y[c] - x[static_cast<std::size_t>(c)]) * (y[c] - x[static_cast<std::size_t>(c)]);
  return std::sqrt(d);
}

// The parameter along side k of s (0: v = lo, 1: u = hi, 2: v = hi, 3: u = lo) where the side passes within tol
// of x strictly between its ends, or NaN. Sampling then Newton on |side(t) - x|^2 (the side is one cubic-like
// Bezier curve, monotone enough between samples).
double side_parameter(const TensorSpline<2>& s, int k, const XY& x, double tol) {
  const Box<2> d = s.domain();
  const int dir = k % 2 == 0 ? 0 : 1;  // the parameter that runs along the side
  const double fixed = k == 0 ? d.lo[1] : k == 1 ? d.hi[0] : k == 2 ? d.hi[1] : d.lo[0];
  const auto point = [&](double t) { return dir == 0 ? Param<2>{t, fixed} : Param<2>{fixed, t}; };
  const double lo = d.lo[dir], hi = d.hi[dir];
  double best = lo, best_d = INFINITY;
  constexpr int samples = 16;
  const int dim = s.dim();
  for (int i = 0; i <= samples; ++i) {
    const double t = lo + (hi - lo) * i / samples;
    double y[3];
    s.eval(point(t), y);
    const double e = point_distance(y, x, dim);
    if (e < best_d) {
      best_d = e;
      best = t;
    }
  }
  double t = best;
  for (int it = 0; it < 30; ++it) {
    double q[9];  // value, d/du, d/dv
    s.eval_derivs(point(t), 1, q);
    double g = 0, h = 0;
    for (int c = 0; c < dim; ++c) {
      const double tc = q[(1 + dir) * dim + c];
      g += (q[c] - x[static_cast<std::size_t>(c)]) * tc;
      h += tc * tc;
    }
    if (h <= 0) break;
    const double step = g / h;
    t = std::clamp(t - step, lo, hi);
    if (std::abs(step) <= 1e-15 * (hi - lo)) break;
  }
  double y[3];
  s.eval(point(t), y);
  if (point_distance(y, x, dim) > tol) return NAN;
  const double margin = 1e-9 * (hi - lo);
  return t > lo + margin && t < hi - margin ? t : NAN;
}

}  // namespace

ConformingPatches conforming_split(std::vector<TensorSpline<2>> patches, double tol) {
  ConformingPatches r;
  r.owner.resize(patches.size());
  std::iota(r.owner.begin(), r.owner.end(), 0);
  for (std::size_t i = 0; i < patches.size(); ++i)
    require(patches[i].count(0) == patches[i].degree(0) + 1 && patches[i].count(1) == patches[i].degree(1) + 1 &&
                (patches[i].dim() == 2 || patches[i].dim() == 3),
            [&] { return "conforming split: patch " + std::to_string(i) + " is not one Bezier element in the plane or in space"; });
  r.patches = std::move(patches);
  const std::size_t limit = 64 * std::max<std::size_t>(r.patches.size(), 1);
  for (;;) {
    // Every patch corner, sorted by x, to find the ones inside a side's bounding box.
    struct Corner {
      XY x;
      std::size_t patch;
    };
    std::vector<Corner> corners;
    for (std::size_t i = 0; i < r.patches.size(); ++i) {
      const Box<2> d = r.patches[i].domain();
      for (const auto& [u, v] : {std::array<double, 2>{d.lo[0], d.lo[1]}, {d.hi[0], d.lo[1]}, {d.hi[0], d.hi[1]}, {d.lo[0], d.hi[1]}})
        corners.push_back({corner_at(r.patches[i], u, v), i});
    }
    std::sort(corners.begin(), corners.end(), [](const Corner& a, const Corner& b) { return a.x[0] < b.x[0]; });
    struct Cut {
      int dir;
      double t;
    };
    std::vector<std::vector<Cut>> cuts(r.patches.size());
    bool any = false;
    for (std::size_t i = 0; i < r.patches.size(); ++i) {
      const TensorSpline<2>& s = r.patches[i];
      double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
      s.control_bounds(lo, hi);
      // Its own corners (most of the corners near a patch are its neighbours' shared ones) and the bounding
      // boxes of its sides' control points (convex hull: a point on a side lies in its box).
      const Box<2> d = s.domain();
      std::array<XY, 4> own;
      std::array<Box<3>, 4> side_box;
      const int dim = s.dim();
      const auto n = s.counts();
      for (int k = 0; k < 4; ++k) {
        const double u = k == 1 || k == 2 ? d.hi[0] : d.lo[0], v = k >= 2 ? d.hi[1] : d.lo[1];
        own[static_cast<std::size_t>(k)] = corner_at(s, u, v);
        Box<3>& b = side_box[static_cast<std::size_t>(k)];
        b = Box<3>::empty();
        for (int t = 0; t < n[k % 2 == 0 ? 0 : 1]; ++t) {
          const int a = k % 2 == 0 ? t : (k == 1 ? n[0] - 1 : 0), c = k % 2 == 0 ? (k == 0 ? 0 : n[1] - 1) : t;
          double x[3] = {0, 0, 0};
          s.control_point(a + n[0] * c, x);
          if (dim == 2) x[2] = 0;
          b.extend(x);
        }
      }
      const auto near_own = [&](const XY& x) {
        return std::any_of(own.begin(), own.end(), [&](const XY& y) { return point_distance(y.data(), x, 3) <= tol; });
      };
      const auto first = std::lower_bound(corners.begin(), corners.end(), lo[0] - tol, [](const Corner& c, double x) { return c.x[0] < x; });
      for (auto c = first; c != corners.end() && c->x[0] <= hi[0] + tol; ++c) {
        if (c->patch == i || c->x[1] < lo[1] - tol || c->x[1] > hi[1] + tol || c->x[2] < lo[2] - tol || c->x[2] > hi[2] + tol ||
            near_own(c->x))
          continue;
        for (int k = 0; k < 4; ++k) {
          const Box<3>& b = side_box[static_cast<std::size_t>(k)];
          bool inside = true;
          for (int e = 0; e < 3; ++e) inside = inside && c->x[static_cast<std::size_t>(e)] >= b.lo[e] - tol && c->x[static_cast<std::size_t>(e)] <= b.hi[e] + tol;
          if (!inside) continue;
          const double t = side_parameter(s, k, c->x, tol);
          if (std::isnan(t)) continue;
          cuts[i].push_back({k % 2 == 0 ? 0 : 1, t});
          any = true;
          break;
        }
      }
    }
    if (!any) break;
    std::vector<TensorSpline<2>> next;
    std::vector<int> owner;
    for (std::size_t i = 0; i < r.patches.size(); ++i) {
      if (cuts[i].empty()) {
        next.push_back(std::move(r.patches[i]));
        owner.push_back(r.owner[i]);
        continue;
      }
      // One cut per pass and patch (its pieces are checked again in the next pass).
      const Cut c = cuts[i].front();
      auto [a, b] = split_at(r.patches[i], c.dir, c.t);
      next.push_back(std::move(a));
      next.push_back(std::move(b));
      owner.insert(owner.end(), 2, r.owner[i]);
    }
    r.patches = std::move(next);
    r.owner = std::move(owner);
    require(r.patches.size() <= limit, [&] {
      return "conforming split: " + std::to_string(r.patches.size()) + " pieces and still corners inside sides; the patches do not tile a domain";
    });
  }
  return r;
}

}  // namespace trivar
