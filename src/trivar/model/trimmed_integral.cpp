#include "trivar/model/trimmed_integral.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <type_traits>

#include <Eigen/Core>

#include "trivar/core/error.hpp"
#include "trivar/core/gauss_legendre.hpp"
#include "trivar/core/parallel.hpp"
#include "trivar/model/line_flux.hpp"

namespace trivar {

namespace {

// Whether the surface is a polynomial along direction `dir` for every fixed parameter of the other direction:
// its weights do not change along `dir` (a cylinder or an extrusion along its rulings, any non-rational face).
bool polynomial_along(const TensorSpline<2>& s, int dir) {
  if (!s.is_rational()) return true;
  const int n0 = s.count(0), n1 = s.count(1);
  for (int j = 0; j < n1; ++j)
    for (int i = 0; i < n0; ++i) {
      const int first = dir == 0 ? s.linear_index({0, j}) : s.linear_index({i, 0});
      if (s.weight(s.linear_index({i, j})) != s.weight(first)) return false;
    }
  return true;
}

bool polynomial(const TensorSpline<1>& c) {
  if (!c.is_rational()) return true;
  for (int i = 1; i < c.count(0); ++i)
    if (c.weight(i) != c.weight(0)) return false;
  return true;
}

// Gauss-Legendre rules by point count, made when first asked for (a face's loops ask for a few counts); the
// references stay valid while more are made.
class RuleCache {
public:
  const QuadratureRule& operator()(int n) {
    auto [it, made] = rules_.try_emplace(n);
    if (made) it->second = gauss_legendre(n);
    return it->second;
  }

private:
  std::map<int, QuadratureRule> rules_;
};

// The most points an exact rule may have before the adaptive rule (three of the default rules at least) is the
// cheaper choice.
constexpr int kMaxExactPoints = 40;

// What a face integrates over its trimmed domain. With a value type V = double: F(S) (S_u x S_v)_x for a given F,
// or (x - shift) (S_u x S_v)_x when F is null (the volume's flux); with V = AreaVec: S_u x S_v, the area vector's
// three components together (one line sum gives all three). The last two allow exact rules.
struct Flux {
  const std::function<double(const std::array<double, 3>&)>* F = nullptr;
  double shift = 0;
};

using AreaVec = Eigen::Vector3d;

template <class V>
V zero_value() {
  if constexpr (std::is_same_v<V, double>)
    return 0.0;
  else
    return V::Zero();
}

// What the adaptive rule compares with its tolerance: for the area vector every component must agree.
double flux_magnitude(double x) { return std::abs(x); }
double flux_magnitude(const AreaVec& v) { return v.cwiseAbs().maxCoeff(); }

// The inner integral runs along the surface direction where it is cheaper (its cost per loop point is the
// number of knot spans times the inner rule's points): with dir = 0, G(u, v) = int_{x0}^{u} flux(s, v) ds and the loop
// integrand is G c_v'; with dir = 1, G(u, v) = int_{x0}^{v} flux(u, s) ds and it is -G c_u' (Green's theorem
// either way: the region integral of flux is the loop integral). The start line x0 is any constant per loop
// (changing it adds H(v) dv, whose integral over a closed loop vanishes): the loop's own least coordinate, so a
// small hole on a large face integrates across its own width only.
//
// With F linear (the volume) and the surface polynomial along dir, flux is a polynomial of degree 3p - 1 in s
// (p the degree along dir: p in F(S), p - 1 in S_s, p in the other tangent, whose rational denominator does not
// depend on s), integrated exactly by ceil(3p / 2) points. If the surface is polynomial in both directions and a
// trimming curve of degree r is too, the loop integrand on a piece between knot-line crossings is a polynomial
// of degree (3p + 3q) r - 1 in the curve parameter (G has total degree 3p + 3q - 1), integrated exactly without
// adaptive halving.
//
// The area vector's fluxes, the components of S_u x S_v, are polynomials of degree 2p - 1 in s under the same
// conditions (and of total degree 2p + 2q - 1), so the volume's rules integrate them exactly too.
template <class V>
class FaceIntegrand {
public:
  FaceIntegrand(const TrimmedFace& f, const Flux& flux, const QuadratureRule& rule, RuleCache& rules)
      : flux_(flux), dir_(inner_direction(f.surface, rule, flux.F == nullptr)),
        line_(f.surface, dir_, inner_rule(f.surface, dir_, rule, flux.F == nullptr, rules)) {
    if (!flux_.F && polynomial_along(f.surface, 0) && polynomial_along(f.surface, 1))
      total_degree_ = 3 * (f.surface.degree(0) + f.surface.degree(1));
  }

  // Gauss points integrating the loop integrand along `c` exactly, or 0 when no exact rule of at most
  // kMaxExactPoints points exists (rational face or curve, or a general F).
  int exact_points(const TensorSpline<1>& c) const {
    if (total_degree_ == 0 || !polynomial(c)) return 0;
    const int n = (total_degree_ * c.degree(0) + 1) / 2;
    return n <= kMaxExactPoints ? std::max(n, 1) : 0;
  }

  int dir() const { return dir_; }

  // The loop integrand at the curve point (u, v) with derivative (du, dv), for the loop's start line x0.
  V loop_density(double u, double v, double du, double dv, double x0) const {
    const double x = dir_ == 0 ? u : v, t = dir_ == 0 ? v : u;
    const double lo = std::min(x0, x), hi = std::max(x0, x);
    V sum = line_sum(t, lo, hi);
    if (x < x0) sum = -sum;
    return dir_ == 0 ? V(sum * dv) : V(-sum * du);
  }

private:
  V line_sum(double t, double lo, double hi) const {
    if constexpr (std::is_same_v<V, double>) {
      return flux_.F ? line_.general(t, lo, hi, *flux_.F) : line_.linear(t, lo, hi, flux_.shift);
    } else {
      const std::array<double, 3> a = line_.area(t, lo, hi);
      return V(a[0], a[1], a[2]);
    }
  }

  // Points per span of the inner rule along `dir`: the exact rule where the volume's flux is a polynomial.
  static int inner_points(const TensorSpline<2>& s, int dir, const QuadratureRule& rule, bool linear) {
    const int n = static_cast<int>(rule.nodes.size());
    return linear && polynomial_along(s, dir) ? std::min(n, std::max((3 * s.degree(dir) + 1) / 2, 1)) : n;
  }

  // The direction whose lines cost fewer flux points per loop point (knot spans times the inner rule's points:
  // a cylinder of one span around is integrated along its axis, 2 points, not around it, 16); u on a tie.
  static int inner_direction(const TensorSpline<2>& s, const QuadratureRule& rule, bool linear) {
    const auto cost = [&](int d) { return (s.knots(d).breakpoints().size() - 1) * static_cast<std::size_t>(inner_points(s, d, rule, linear)); };
    return cost(1) < cost(0) ? 1 : 0;
  }

  static const QuadratureRule& inner_rule(const TensorSpline<2>& s, int dir, const QuadratureRule& rule, bool linear,
                                          RuleCache& rules) {
    const int n = inner_points(s, dir, rule, linear);
    return n < static_cast<int>(rule.nodes.size()) ? rules(n) : rule;
  }

  Flux flux_;
  int dir_;
  LineFlux line_;
  int total_degree_ = 0;  // 3p + 3q when the loop integrand is a polynomial on polynomial curves, else 0
};

// The loop integral over one smooth piece [a, b] of a trimming curve.
template <class V>
V piece(const FaceIntegrand<V>& g, const TensorSpline<1>& c, const QuadratureRule& rule, double a, double b, double x0) {
  V sum = zero_value<V>();
  for (std::size_t q = 0; q < rule.nodes.size(); ++q) {
    const double t = a + rule.nodes[q] * (b - a);
    double d[4];
    c.eval_derivs({t}, 1, d);  // (u, v), (u', v')
    sum += rule.weights[q] * (b - a) * g.loop_density(d[0], d[1], d[2], d[3], x0);
  }
  return sum;
}

template <class V>
V adaptive(const FaceIntegrand<V>& g, const TensorSpline<1>& c, const QuadratureRule& rule, double a, double b,
           double x0, const V& whole, double tol, int depth) {
  const double m = 0.5 * (a + b);
  const V left = piece(g, c, rule, a, m, x0), right = piece(g, c, rule, m, b, x0);
  // Kinks of G (where the curve crosses a knot line of the surface) slow convergence; halving isolates them.
  if (depth == 0 || flux_magnitude(V(left + right - whole)) <= tol) return V(left + right);
  return V(adaptive(g, c, rule, a, m, x0, left, tol / 2, depth - 1) + adaptive(g, c, rule, m, b, x0, right, tol / 2, depth - 1));
}

// The loop integral over [a, b]: the rule's sum, accepted when a rule of half as many points agrees with it
// within the tolerance (the error of the finer rule is far below their difference on smooth pieces: one piece
// costs 1.5 rules instead of the 3 of comparing halves), else adaptive halving.
template <class V>
V estimated(const FaceIntegrand<V>& g, const TensorSpline<1>& c, const QuadratureRule& rule, const QuadratureRule& coarse,
            double a, double b, double x0, double tol, int depth) {
  const V whole = piece(g, c, rule, a, b, x0);
  if (flux_magnitude(V(whole - piece(g, c, coarse, a, b, x0))) <= tol) return whole;
  return adaptive(g, c, rule, a, b, x0, whole, tol, depth);
}

// The span [a, b] of a trimming curve cut where it crosses the surface's knot lines, the kinks of the loop
// integrand (halving would only isolate them): sign changes of u - x (v - x) on eight sub-intervals, each
// refined by false position with the Illinois modification (superlinear: a handful of curve points where
// bisection to rounding took fifty) until u - x is at rounding level of the span's coordinates or the bracket
// is at rounding level of the span. A crossing that touches a knot line without changing sides is left to the
// halving.
void knot_line_crossings(const TensorSpline<1>& c, double a, double b, const std::array<std::vector<double>, 2>& knot_lines,
                         std::vector<double>& cuts) {
  constexpr int kSamples = 8;
  cuts = {a, b};
  if (knot_lines[0].size() <= 2 && knot_lines[1].size() <= 2) return;  // one polynomial piece: no kinks
  std::array<std::array<double, 2>, kSamples + 1> uv;
  for (int i = 0; i <= kSamples; ++i) c.eval({a + (b - a) * i / kSamples}, uv[static_cast<std::size_t>(i)].data());
  for (std::size_t k = 0; k < 2; ++k) {
    const std::vector<double>& lines = knot_lines[k];
    double extent = 0;
    for (const auto& p : uv) extent = std::max(extent, std::abs(p[k]));
    const double f_tol = 1e-15 * std::max(extent, std::abs(lines.front()) + std::abs(lines.back()));
    for (std::size_t j = 1; j + 1 < lines.size(); ++j) {  // the domain's ends are no kinks inside it
      const double x = lines[j];
      for (int i = 0; i < kSamples; ++i) {
        double f_lo = uv[static_cast<std::size_t>(i)][k] - x, f_hi = uv[static_cast<std::size_t>(i) + 1][k] - x;
        if (!(f_lo * f_hi < 0)) continue;
        double lo = a + (b - a) * i / kSamples, hi = a + (b - a) * (i + 1) / kSamples, m = 0.5 * (lo + hi);
        int kept = 0;  // which end stayed last time: -1 low, 1 high
        for (int it = 0; it < 60 && hi - lo > 1e-15 * (std::abs(lo) + std::abs(hi)); ++it) {
          m = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
          if (!(m > lo && m < hi)) m = 0.5 * (lo + hi);
          double p[2];
          c.eval({m}, p);
          const double f = p[k] - x;
          if (std::abs(f) <= f_tol) break;
          if (f * f_lo > 0) {
            lo = m;
            f_lo = f;
            if (kept == 1) f_hi *= 0.5;
            kept = 1;
          } else {
            hi = m;
            f_hi = f;
            if (kept == -1) f_lo *= 0.5;
            kept = -1;
          }
          m = 0.5 * (lo + hi);
        }
        cuts.push_back(m);
      }
    }
  }
  std::sort(cuts.begin(), cuts.end());
}

// The face's term: its loop integral, signed by its orientation.
template <class V>
V face_integral(const TrimmedFace& f, const Flux& flux, const QuadratureRule& rule, double relative_tolerance) {
  constexpr int kMaxHalvings = 12;
  RuleCache rules;
  const int coarse = std::max(1, static_cast<int>(rule.nodes.size()) / 2);
  const FaceIntegrand<V> g(f, flux, rule, rules);
  // The face's scale: |G| is at most |F| |S_u x S_v| times the domain, estimated from the control box (an
  // area for the area vector, a volume otherwise).
  std::array<double, 3> lo, hi;
  f.surface.control_bounds(lo.data(), hi.data());
  double scale = 0;
  for (int k = 0; k < 3; ++k) scale = std::max(scale, hi[k] - lo[k]);
  const double tol = relative_tolerance * std::max(std::is_same_v<V, double> ? scale * scale * scale : scale * scale, 1e-300);
  const std::array<std::vector<double>, 2> knot_lines{f.surface.knots(0).breakpoints(), f.surface.knots(1).breakpoints()};
  V face = zero_value<V>();
  std::vector<double> cuts;
  const auto along = [&](const TensorSpline<1>& c, double x0) {
    const std::vector<double> br = c.knots(0).breakpoints();
    const int exact = g.exact_points(c);
    for (std::size_t s = 0; s + 1 < br.size(); ++s) {
      knot_line_crossings(c, br[s], br[s + 1], knot_lines, cuts);
      for (std::size_t k = 0; k + 1 < cuts.size(); ++k)
        face += exact > 0 ? piece(g, c, rules(exact), cuts[k], cuts[k + 1], x0)
                          : estimated(g, c, rule, rules(coarse), cuts[k], cuts[k + 1], x0, tol, kMaxHalvings);
    }
  };
  for (const TrimLoop& loop : f.loops) {
    // The loop's start line: the least coordinate of its curves' control points along the inner direction
    // (the curves lie in their control hulls), kept inside the face's domain.
    double x0 = std::numeric_limits<double>::infinity();
    for (const TrimCurve& tc : loop.curves) {
      double clo[2], chi[2];
      tc.pcurve.control_bounds(clo, chi);
      x0 = std::min(x0, clo[g.dir()]);
    }
    const Box<2> dom = f.surface.domain();
    x0 = std::isfinite(x0) ? std::clamp(x0, dom.lo[g.dir()], dom.hi[g.dir()]) : dom.lo[g.dir()];
    for (std::size_t k = 0; k < loop.curves.size(); ++k) {
      const TensorSpline<1>& c = loop.curves[k].pcurve;
      along(c, x0);
      // Green's theorem needs the loop closed: where a curve ends off the next one's start (a kernel's curves
      // meet within its vertex tolerance only, 1e-7 and more apart after Booleans of Booleans), the segment
      // across the gap closes it, so the result is off by the gap's square rather than by G times the gap.
      const TensorSpline<1>& next = loop.curves[(k + 1) % loop.curves.size()].pcurve;
      double end[2], start[2];
      c.eval({c.domain().hi[0]}, end);
      next.eval({next.domain().lo[0]}, start);
      if (end[0] != start[0] || end[1] != start[1])
        along(TensorSpline<1>({KnotVector(1, {0, 0, 1, 1})}, 2, false, {end[0], end[1], start[0], start[1]}), x0);
    }
  }
  return f.reversed ? V(-face) : face;
}

void check_options(const TrimmedIntegralOptions& opts) {
  require(opts.points >= 1 && opts.relative_tolerance > 0, "trimmed integral: points must be >= 1 and the tolerance > 0");
}

// term(i) for i < n on all threads, dealt round-robin (faces differ in cost by orders of magnitude, and
// neighbours in the list are often alike); the caller sums them in order, so its result does not depend on
// the thread count. `term` must be pure.
template <class Term>
auto parallel_terms(std::ptrdiff_t n, const Term& term) {
  const int threads = static_cast<int>(std::min<std::ptrdiff_t>(resolve_threads(0), std::max<std::ptrdiff_t>(n, 1)));
  std::vector<decltype(term(std::ptrdiff_t{0}))> terms(static_cast<std::size_t>(n));
  parallel_for(threads, threads, [&](std::ptrdiff_t k) {
    for (std::ptrdiff_t i = k; i < n; i += threads) terms[static_cast<std::size_t>(i)] = term(i);
  });
  return terms;
}

}  // namespace

double trimmed_integral(const TrimmedBoundary& b, const std::function<double(const std::array<double, 3>&)>& antiderivative,
                        const TrimmedIntegralOptions& opts) {
  check_options(opts);
  const QuadratureRule rule = gauss_legendre(opts.points);
  double total = 0;
  for (const TrimmedFace& f : b.faces) total += face_integral<double>(f, {.F = &antiderivative}, rule, opts.relative_tolerance);
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
  double total = 0;
  for (double t : parallel_terms(static_cast<std::ptrdiff_t>(b.faces.size()), [&](std::ptrdiff_t i) {
         return face_integral<double>(b.faces[static_cast<std::size_t>(i)], {.shift = x0}, rule, opts.relative_tolerance);
       }))
    total += t;
  return total;
}

std::array<double, 3> trimmed_area_vector(const TrimmedBoundary& b, const TrimmedIntegralOptions& opts) {
  check_options(opts);
  const QuadratureRule rule = gauss_legendre(opts.points);
  AreaVec total = AreaVec::Zero();
  for (const AreaVec& t : parallel_terms(static_cast<std::ptrdiff_t>(b.faces.size()), [&](std::ptrdiff_t i) {
         return face_integral<AreaVec>(b.faces[static_cast<std::size_t>(i)], {}, rule, opts.relative_tolerance);
       }))
    total += t;
  return {total[0], total[1], total[2]};
}

}  // namespace trivar
