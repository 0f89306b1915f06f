#include "trivar/model/trimmed_integral.hpp"

#include <cmath>

#include "trivar/core/error.hpp"
#include "trivar/core/gauss_legendre.hpp"

namespace trivar {

namespace {

class FaceIntegrand {
public:
  FaceIntegrand(const TrimmedFace& f, const std::function<double(const std::array<double, 3>&)>& F,
                const QuadratureRule& rule)
      : f_(f), F_(F), rule_(rule), breaks_(f.surface.knots(0).breakpoints()) {}

  // F(S(u, v)) (S_u x S_v)_x, the x-flux density in parameter space.
  double flux(double u, double v) const {
    double d[9];
    f_.surface.eval_derivs({u, v}, 1, d);  // S, S_u, S_v
    const double nx = d[4] * d[8] - d[5] * d[7];
    return F_({d[0], d[1], d[2]}) * nx;
  }

  // G(u, v) = int_{u0}^{u} flux(s, v) ds, Gauss over the surface's u-spans (the integrand is smooth in each).
  double G(double u, double v) const {
    double sum = 0;
    for (std::size_t s = 0; s + 1 < breaks_.size() && breaks_[s] < u; ++s) {
      const double a = breaks_[s], b = std::min(breaks_[s + 1], u);
      if (b <= a) continue;
      for (std::size_t q = 0; q < rule_.nodes.size(); ++q) sum += rule_.weights[q] * (b - a) * flux(a + rule_.nodes[q] * (b - a), v);
    }
    return sum;
  }

private:
  const TrimmedFace& f_;
  const std::function<double(const std::array<double, 3>&)>& F_;
  const QuadratureRule& rule_;
  std::vector<double> breaks_;
};

// int_a^b G(c(t)) c_v'(t) dt over one smooth piece of a trimming curve.
double piece(const FaceIntegrand& g, const TensorSpline<1>& c, const QuadratureRule& rule, double a, double b) {
  double sum = 0;
  for (std::size_t q = 0; q < rule.nodes.size(); ++q) {
    const double t = a + rule.nodes[q] * (b - a);
    double d[4];
    c.eval_derivs({t}, 1, d);  // (u, v), (u', v')
    sum += rule.weights[q] * (b - a) * g.G(d[0], d[1]) * d[3];
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

}  // namespace

double trimmed_integral(const TrimmedBoundary& b, const std::function<double(const std::array<double, 3>&)>& antiderivative,
                        const TrimmedIntegralOptions& opts) {
  require(opts.points >= 1 && opts.relative_tolerance > 0, "trimmed integral: points must be >= 1 and the tolerance > 0");
  constexpr int kMaxHalvings = 12;
  const QuadratureRule rule = gauss_legendre(opts.points);
  double total = 0;
  for (const TrimmedFace& f : b.faces) {
    const FaceIntegrand g(f, antiderivative, rule);
    // The face's scale: |G| is at most |F| |S_u x S_v| times the domain, estimated from the control box.
    std::array<double, 3> lo, hi;
    f.surface.control_bounds(lo.data(), hi.data());
    double scale = 0;
    for (int k = 0; k < 3; ++k) scale = std::max(scale, hi[k] - lo[k]);
    const double tol = opts.relative_tolerance * std::max(scale * scale * scale, 1e-300);
    double face = 0;
    const auto along = [&](const TensorSpline<1>& c) {
      const std::vector<double> br = c.knots(0).breakpoints();
      for (std::size_t s = 0; s + 1 < br.size(); ++s)
        face += adaptive(g, c, rule, br[s], br[s + 1], piece(g, c, rule, br[s], br[s + 1]), tol, kMaxHalvings);
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
    total += f.reversed ? -face : face;
  }
  return total;
}

double trimmed_volume(const TrimmedBoundary& b, const TrimmedIntegralOptions& opts) {
  // F = x - x0 with x0 left of the region keeps F small and of one sign (less cancellation).
  double x0 = 0;
  if (!b.mesh.vertices.empty()) {
    x0 = b.mesh.vertices.front()[0];
    for (const auto& v : b.mesh.vertices) x0 = std::min(x0, v[0]);
  }
  return trimmed_integral(b, [x0](const std::array<double, 3>& x) { return x[0] - x0; }, opts);
}

}  // namespace trivar
