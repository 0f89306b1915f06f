#include "trivar/spline/jacobian.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <span>
#include <string>
#include <tuple>
#include <vector>

#include "trivar/core/error.hpp"
#include "trivar/core/parallel.hpp"
#include "trivar/spline/bernstein.hpp"
#include "trivar/spline/bezier_extraction.hpp"

namespace trivar {

namespace {

// Determinant of an n x n matrix m[row][col] of polynomials whose columns each share one degree. Laplace
// expansion along the last used column over all row subsets: the minor of rows S and the first |S| columns
// reuses the minors of size |S| - 1, so a 4 x 4 determinant costs 28 products instead of 72.
template <int D>
Bernstein<D> determinant(const std::vector<std::vector<Bernstein<D>>>& m) {
  const int n = static_cast<int>(m.size());
  std::vector<Bernstein<D>> minor(std::size_t{1} << n);
  for (int i = 0; i < n; ++i) minor[std::size_t{1} << i] = m[i][0];
  for (int size = 2; size <= n; ++size) {
    for (unsigned S = 0; S < (1u << n); ++S) {
      if (std::popcount(S) != size) continue;
      Bernstein<D> acc;
      int r = 0;
      for (int i = 0; i < n; ++i) {
        if (!(S >> i & 1u)) continue;
        Bernstein<D> term = m[i][size - 1] * minor[S ^ (1u << i)];
        if ((r + size - 1) % 2) term *= -1.0;
        acc = r == 0 ? std::move(term) : acc + term;
        ++r;
      }
      minor[S] = std::move(acc);
    }
  }
  return minor[(std::size_t{1} << n) - 1];
}

constexpr double kEps = std::numeric_limits<double>::epsilon();

double max_abs(const std::span<const double> v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

// On one element: N = det J (polynomial) or N = w^(D+1) det J and W = w^(D+1) raised to a common degree
// (rational), derivatives taken with respect to the global parameters, and `error`, a bound on the
// floating-point error of every coefficient of N (polynomial) or of every ratio N_i / W_i (rational) on the
// element and its sub-boxes down to max_depth.
template <int D>
struct ElementDet {
  Bernstein<D> n, w;
  double error = 0;
};

// The error bound is a first-order a-priori estimate in the style of Higham's gamma_k, with a factor 2 of
// safety: the Bezier net is taken exact to 2 ulps of its row magnitude, a difference quotient
// p (P_{i+1} - P_i) / h then errs by 4 ulps of p / h times that magnitude, each Bernstein product coefficient
// by (terms + 4) ulps of the product of its factors' largest coefficients, and each de Casteljau level by
// degree ulps of the largest coefficient. Column magnitudes C_k = sum over rows of the largest coefficient
// bound every coefficient of every partial Laplace sum by prod C_k.
template <int D>
ElementDet<D> element_det(const BezierElement<D>& e, int max_depth) {
  const int st = e.stride(), rows = e.rational ? D + 1 : D, first_deriv = e.rational ? 1 : 0;
  int npts = 1;
  for (int k = 0; k < D; ++k) npts *= e.degrees[k] + 1;
  std::vector<std::vector<Bernstein<D>>> m(rows, std::vector<Bernstein<D>>(rows));
  std::vector<double> magnitude(rows, 0.0), input_error(rows, 0.0);
  int terms = 0;
  for (int r = 0; r < rows; ++r) {
    // The weight row first: det[(w, w x), d(w, w x)] = w^(D+1) det J with this order.
    const int c = e.rational ? (r == 0 ? D : r - 1) : r;
    std::vector<double> v(npts);
    for (int q = 0; q < npts; ++q) v[q] = e.coefs[static_cast<std::size_t>(q) * st + c];
    const Bernstein<D> f(e.degrees, std::move(v));
    const double fmax = max_abs(f.coefs());
    for (int k = 0; k < D; ++k) {
      Bernstein<D>& d = m[r][first_deriv + k];
      d = f.derivative(k);
      d *= 1.0 / e.domain.extent(k);
      magnitude[first_deriv + k] += max_abs(d.coefs());
      input_error[first_deriv + k] += 4 * kEps * e.degrees[k] / e.domain.extent(k) * fmax;
      terms = std::max(terms, d.size());
    }
    if (e.rational) {
      m[r][0] = f;
      magnitude[0] += fmax;
      input_error[0] += 2 * kEps * fmax;
    }
  }
  ElementDet<D> out;
  out.n = determinant(m);
  double product = 1, propagated = 0;
  for (int k = 0; k < rows; ++k) product *= magnitude[k];
  for (int k = 0; k < rows; ++k) {
    double others = input_error[k];
    for (int j = 0; j < rows; ++j)
      if (j != k) others *= magnitude[j];
    propagated += others;
  }
  int top_degree = 0;
  if (e.rational) {
    // W = w^(D+1) with N at the same degree: det J = sum (N_i / W_i) W_i B_i / sum W_j B_j is a convex
    // combination of the ratios, which therefore bound it and converge to it under subdivision.
    out.w = m[0][0];
    for (int k = 0; k < D; ++k) out.w = out.w * m[0][0];
    Ints<D> common{};
    for (int k = 0; k < D; ++k) common[k] = std::max(out.n.degree(k), out.w.degree(k));
    out.n = out.n.elevate(common);
    out.w = out.w.elevate(common);
  }
  for (int k = 0; k < D; ++k) top_degree = std::max(top_degree, out.n.degree(k));
  const double steps = rows * (terms + 4) + max_depth * top_degree + (e.rational ? top_degree + 4 : 0);
  const double n_error = 2 * (propagated + steps * kEps * product);
  if (e.rational) {
    const double w_relative = 2 * steps * kEps, w_min = out.w.min_coef();
    out.error = (n_error + w_relative * max_abs(out.n.coefs())) / w_min;
  } else {
    out.error = n_error;
  }
  return out;
}

// A sub-box [lo, hi] (element-local coordinates in [0,1]^D) with the pieces of N and W on it.
template <int D>
struct Piece {
  Bernstein<D> n, w;
  Param<D> lo{}, hi{};
  double lower = 0;
  int depth = 0;
};

template <int D>
struct ElementResult {
  double lower = std::numeric_limits<double>::infinity();
  double value = std::numeric_limits<double>::infinity();
  Param<D> where{};
  int subdivisions = 0;
};

template <int D>
class ElementRefiner {
public:
  ElementRefiner(const BezierElement<D>& e, const JacobianOptions& o) : e_(e), o_(o) {}

  ElementResult<D> run() {
    ElementDet<D> det = element_det(e_, o_.max_depth);
    Piece<D> root;
    root.n = std::move(det.n);
    root.w = std::move(det.w);
    root.hi.fill(1.0);
    settle(root);
    std::vector<Piece<D>> heap;
    heap.push_back(std::move(root));
    // Lowest lower bound first, so the smallest corner value found drops fastest and prunes the rest.
    const auto later = [](const Piece<D>& a, const Piece<D>& b) { return a.lower > b.lower; };
    while (!heap.empty()) {
      if (heap.front().lower >= res_.value - o_.relative_gap * std::abs(res_.value)) {
        res_.lower = std::min(res_.lower, heap.front().lower);
        break;
      }
      std::pop_heap(heap.begin(), heap.end(), later);
      Piece<D> p = std::move(heap.back());
      heap.pop_back();
      if (p.depth >= o_.max_depth) {
        res_.lower = std::min(res_.lower, p.lower);
        continue;
      }
      const int dir = split_direction(p);
      auto [nl, nr] = p.n.subdivide(dir, 0.5);
      Piece<D> a, b;
      a.n = std::move(nl);
      b.n = std::move(nr);
      if (e_.rational) std::tie(a.w, b.w) = p.w.subdivide(dir, 0.5);
      a.lo = b.lo = p.lo;
      a.hi = b.hi = p.hi;
      a.hi[dir] = b.lo[dir] = 0.5 * (p.lo[dir] + p.hi[dir]);
      a.depth = b.depth = p.depth + 1;
      ++res_.subdivisions;
      for (Piece<D>* c : {&a, &b}) {
        settle(*c);
        heap.push_back(std::move(*c));
        std::push_heap(heap.begin(), heap.end(), later);
      }
    }
    res_.lower -= det.error;
    return res_;
  }

private:
  // Lower bound of det J on the piece, and its corner values offered as the element minimum.
  void settle(Piece<D>& p) {
    p.lower = e_.rational ? ratios(p).min_coef() : p.n.min_coef();
    for (int c = 0; c < (1 << D); ++c) {
      double v = p.n.corner(c);
      if (e_.rational) v /= p.w.corner(c);
      if (v < res_.value) {
        res_.value = v;
        for (int k = 0; k < D; ++k) {
          const double t = (c >> k) & 1 ? p.hi[k] : p.lo[k];
          res_.where[k] = (1.0 - t) * e_.domain.lo[k] + t * e_.domain.hi[k];
        }
      }
    }
  }

  // The ratios N_i / W_i of a rational piece: a net (not a polynomial) whose range bounds det J.
  static Bernstein<D> ratios(const Piece<D>& p) {
    Bernstein<D> r = p.n;
    const auto w = p.w.coefs();
    auto c = r.coefs();
    for (std::size_t i = 0; i < c.size(); ++i) c[i] /= w[i];
    return r;
  }

  // The direction in which the bounding net varies most, so that halving it tightens the bound most.
  int split_direction(const Piece<D>& p) const {
    const Bernstein<D> net = e_.rational ? ratios(p) : Bernstein<D>();
    const Bernstein<D>& b = e_.rational ? net : p.n;
    int best = 0;
    double best_score = -1;
    for (int k = 0; k < D; ++k) {
      const double score = b.variation(k);
      if (score > best_score) {
        best_score = score;
        best = k;
      }
    }
    return best;
  }

  const BezierElement<D>& e_;
  const JacobianOptions& o_;
  ElementResult<D> res_;
};

}  // namespace

template <int D>
JacobianReport<D> check_jacobian(const TensorSpline<D>& s, const JacobianOptions& opts) {
  require(s.dim() == D, "check_jacobian: control dimension " + std::to_string(s.dim()) +
                            " differs from the parametric dimension " + std::to_string(D));
  require(opts.max_depth >= 0, "check_jacobian: negative max_depth " + std::to_string(opts.max_depth));
  require(opts.relative_gap >= 0, "check_jacobian: negative relative_gap " + std::to_string(opts.relative_gap));
  const std::vector<BezierElement<D>> elements = bezier_elements(s);
  std::vector<ElementResult<D>> results(elements.size());
  parallel_for(static_cast<std::ptrdiff_t>(elements.size()), 0,
               [&](std::ptrdiff_t i) { results[i] = ElementRefiner<D>(elements[i], opts).run(); });
  JacobianReport<D> rep;
  rep.elements = static_cast<int>(elements.size());
  rep.min_lower_bound = std::numeric_limits<double>::infinity();
  rep.min_value = std::numeric_limits<double>::infinity();
  for (const auto& r : results) {
    rep.min_lower_bound = std::min(rep.min_lower_bound, r.lower);
    if (r.value < rep.min_value) {
      rep.min_value = r.value;
      rep.where = r.where;
    }
    rep.subdivisions += r.subdivisions;
  }
  rep.valid = rep.min_lower_bound > 0;
  rep.invalid = rep.min_value <= 0;
  return rep;
}

template JacobianReport<1> check_jacobian(const TensorSpline<1>&, const JacobianOptions&);
template JacobianReport<2> check_jacobian(const TensorSpline<2>&, const JacobianOptions&);
template JacobianReport<3> check_jacobian(const TensorSpline<3>&, const JacobianOptions&);

}  // namespace trivar
