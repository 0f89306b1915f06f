#include "trivar/model/trimmed_integral.hpp"

#include <algorithm>
#include <cmath>

#include "trivar/core/error.hpp"
#include "trivar/core/gauss_legendre.hpp"
#include "trivar/core/parallel.hpp"

namespace trivar {

namespace {

// The inner integral runs along the surface direction with fewer knot spans (its cost per loop point is
// the number of spans times the rule's points): with dir = 0, G(u, v) = int_{u0}^{u} flux(s, v) ds and the loop
// integrand is G c_v'; with dir = 1, G(u, v) = int_{v0}^{v} flux(u, s) ds and it is -G c_u' (Green's theorem
// either way: the region integral of flux is the loop integral).
class FaceIntegrand {
public:
  FaceIntegrand(const TrimmedFace& f, const std::function<double(const std::array<double, 3>&)>& F,
                const QuadratureRule& rule)
      : f_(f), F_(F), rule_(rule) {
    const std::vector<double> bu = f.surface.knots(0).breakpoints(), bv = f.surface.knots(1).breakpoints();
    dir_ = bv.size() < bu.size() ? 1 : 0;
    breaks_ = dir_ == 0 ? bu : bv;
  }

  // F(S(u, v)) (S_u x S_v)_x, the x-flux density in parameter space.
  double flux(double u, double v) const {
    double d[9];
    f_.surface.eval_derivs({u, v}, 1, d);  // S, S_u, S_v
    const double nx = d[4] * d[8] - d[5] * d[7];
    return F_({d[0], d[1], d[2]}) * nx;
  }

  // The loop integrand at the curve point (u, v) with derivative (du, dv).
  double loop_density(double u, double v, double du, double dv) const {
    const double x = dir_ == 0 ? u : v;
    double sum = 0;
    for (std::size_t s = 0; s + 1 < breaks_.size() && breaks_[s] < x; ++s) {
      const double a = breaks_[s], b = std::min(breaks_[s + 1], x);
      if (b <= a) continue;
      for (std::size_t q = 0; q < rule_.nodes.size(); ++q) {
        const double y = a + rule_.nodes[q] * (b - a);
        sum += rule_.weights[q] * (b - a) * (dir_ == 0 ? flux(y, v) : flux(u, y));
      }
    }
    return dir_ == 0 ? sum * dv : -sum * du;
  }

private:
  const TrimmedFace& f_;
  const std::function<double(const std::array<double, 3>&)>& F_;
  const QuadratureRule& rule_;
  int dir_ = 0;
  std::vector<double> breaks_;
};

// The loop integral over one smooth piece [a, b] of a trimming curve.
double piece(const FaceIntegrand& g, const TensorSpline<1>& c, const QuadratureRule& rule, double a, double b) {
  double sum = 0;
  for (std::size_t q = 0; q < rule.nodes.size(); ++q) {
    const double t = a + rule.nodes[q] * (b - a);
    double d[4];
    c.eval_derivs({t}, 1, d);  // (u, v), (u', v')
    sum += rule.weights[q] * (b - a) * g.loop_density(d[0], d[1], d[2], d[3]);
  }
  return sum;
}

double adaptive(const FaceIntegrand& g, const TensorSpline<1>& c, const QuadratureRule& rule, double a, double b,
                double whole, double tol, int depth) {
  const double m = 0.5 * (a + b);
  const double left = piece(g, c, rule, a, m), right = piece(g, c, rule, m, b);
  // Kinks of G (where the curve crosses a knot line of the surface) slow convergence; halving isolates them.
  if (depth == 0 || std::abs(left + right - whole) <= tol) return left + right;
  return adaptive(g, c, rule, a, m, left, tol / 2, depth - 1) + adaptive(g, c, rule, m, b, right, tol / 2, depth - 1);
}

// The span [a, b] of a trimming curve cut where it crosses the surface's knot lines, the kinks of the loop
// integrand (halving would only isolate them): sign changes of u - x (v - x) on eight sub-intervals, refined by
// bisection to rounding. A crossing that touches a knot line without changing sides is left to the halving.
void knot_line_crossings(const TensorSpline<1>& c, double a, double b, const std::array<std::vector<double>, 2>& knot_lines,
                         std::vector<double>& cuts) {
  constexpr int kSamples = 8;
  cuts = {a, b};
  std::array<std::array<double, 2>, kSamples + 1> uv;
  for (int i = 0; i <= kSamples; ++i) c.eval({a + (b - a) * i / kSamples}, uv[static_cast<std::size_t>(i)].data());
  for (std::size_t k = 0; k < 2; ++k) {
    const std::vector<double>& lines = knot_lines[k];
    for (std::size_t j = 1; j + 1 < lines.size(); ++j) {  // the domain's ends are no kinks inside it
      const double x = lines[j];
      for (int i = 0; i < kSamples; ++i) {
        const double f0 = uv[static_cast<std::size_t>(i)][k] - x, f1 = uv[static_cast<std::size_t>(i) + 1][k] - x;
        if (!(f0 * f1 < 0)) continue;
        double lo = a + (b - a) * i / kSamples, hi = a + (b - a) * (i + 1) / kSamples;
        for (int it = 0; it < 60 && hi - lo > 1e-15 * (std::abs(lo) + std::abs(hi)); ++it) {
          const double m = 0.5 * (lo + hi);
          double p[2];
          c.eval({m}, p);
          ((p[k] - x) * f0 > 0 ? lo : hi) = m;
        }
        cuts.push_back(0.5 * (lo + hi));
      }
    }
  }
  std::sort(cuts.begin(), cuts.end());
}

// The face's term: its loop integral, signed by its orientation.
double face_integral(const TrimmedFace& f, const std::function<double(const std::array<double, 3>&)>& antiderivative,
                     const QuadratureRule& rule, double relative_tolerance) {
  constexpr int kMaxHalvings = 12;
  const FaceIntegrand g(f, antiderivative, rule);
  // The face's scale: |G| is at most |F| |S_u x S_v| times the domain, estimated from the control box.
  std::array<double, 3> lo, hi;
  f.surface.control_bounds(lo.data(), hi.data());
  double scale = 0;
  for (int k = 0; k < 3; ++k) scale = std::max(scale, hi[k] - lo[k]);
  const double tol = relative_tolerance * std::max(scale * scale * scale, 1e-300);
  const std::array<std::vector<double>, 2> knot_lines{f.surface.knots(0).breakpoints(), f.surface.knots(1).breakpoints()};
  double face = 0;
  std::vector<double> cuts;
  const auto along = [&](const TensorSpline<1>& c) {
    const std::vector<double> br = c.knots(0).breakpoints();
    for (std::size_t s = 0; s + 1 < br.size(); ++s) {
      knot_line_crossings(c, br[s], br[s + 1], knot_lines, cuts);
      for (std::size_t k = 0; k + 1 < cuts.size(); ++k)
        face += adaptive(g, c, rule, cuts[k], cuts[k + 1], piece(g, c, rule, cuts[k], cuts[k + 1]), tol, kMaxHalvings);
    }
  };
  for (const TrimLoop& loop : f.loops)
    for (std::size_t k = 0; k < loop.curves.size(); ++k) {
      const TensorSpline<1>& c = loop.curves[k].pcurve;
      along(c);
      // Green's theorem needs the loop closed: where a curve ends off the next one's start (a kernel's curves
      // meet within its vertex tolerance only, 1e-7 and more apart after Booleans of Booleans), the segment
      // across the gap closes it, so the result is off by the gap's square rather than by G times the gap.
      const TensorSpline<1>& next = loop.curves[(k + 1) % loop.curves.size()].pcurve;
      double end[2], start[2];
      c.eval({c.domain().hi[0]}, end);
      next.eval({next.domain().lo[0]}, start);
      if (end[0] != start[0] || end[1] != start[1])
        along(TensorSpline<1>({KnotVector(1, {0, 0, 1, 1})}, 2, false, {end[0], end[1], start[0], start[1]}));
    }
  return f.reversed ? -face : face;
}

void check_options(const TrimmedIntegralOptions& opts) {
  require(opts.points >= 1 && opts.relative_tolerance > 0, "trimmed integral: points must be >= 1 and the tolerance > 0");
}

}  // namespace

double trimmed_integral(const TrimmedBoundary& b, const std::function<double(const std::array<double, 3>&)>& antiderivative,
                        const TrimmedIntegralOptions& opts) {
  check_options(opts);
  const QuadratureRule rule = gauss_legendre(opts.points);
  double total = 0;
  for (const TrimmedFace& f : b.faces) total += face_integral(f, antiderivative, rule, opts.relative_tolerance);
  return total;
}

double trimmed_volume(const TrimmedBoundary& b, const TrimmedIntegralOptions& opts) {
  // F = x - x0 with x0 left of the region keeps F small and of one sign (less cancellation).
  double x0 = 0;
  if (!b.mesh.vertices.empty()) {
    x0 = b.mesh.vertices.front()[0];
    for (const auto& v : b.mesh.vertices) x0 = std::min(x0, v[0]);
  }
  check_options(opts);
  const QuadratureRule rule = gauss_legendre(opts.points);
  const std::function<double(const std::array<double, 3>&)> F = [x0](const std::array<double, 3>& x) { return x[0] - x0; };
  // The faces on all threads (F is pure), dealt round-robin (faces differ in cost by orders of magnitude, and
  // neighbours in the list are often alike); their terms summed in face order, so the result does not depend
  // on the thread count.
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(b.faces.size());
  const int threads = static_cast<int>(std::min<std::ptrdiff_t>(resolve_threads(0), std::max<std::ptrdiff_t>(n, 1)));
  std::vector<double> terms(b.faces.size());
  parallel_for(threads, threads, [&](std::ptrdiff_t k) {
    for (std::ptrdiff_t i = k; i < n; i += threads)
      terms[static_cast<std::size_t>(i)] = face_integral(b.faces[static_cast<std::size_t>(i)], F, rule, opts.relative_tolerance);
  });
  double total = 0;
  for (double t : terms) total += t;
  return total;
}

}  // namespace trivar
