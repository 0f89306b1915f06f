#include "trivar/model/trimmed_integral.hpp"

#include <algorithm>
#include <cmath>

#include "trivar/core/error.hpp"
#include "trivar/core/gauss_legendre.hpp"
#include "trivar/core/parallel.hpp"

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
  double face = 0;
  for (const TrimLoop& loop : f.loops)
    for (const TrimCurve& tc : loop.curves) {
      const std::vector<double> br = tc.pcurve.knots(0).breakpoints();
      for (std::size_t s = 0; s + 1 < br.size(); ++s)
        face += adaptive(g, tc.pcurve, rule, br[s], br[s + 1], piece(g, tc.pcurve, rule, br[s], br[s + 1]), tol, kMaxHalvings);
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
