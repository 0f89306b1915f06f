#include "trivar/spline/jacobian.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
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

// det J of a polynomial element, or the homogeneous numerator N = w^(D+1) det J and the weight w of a
// rational one, with derivatives taken with respect to the global parameters.
template <int D>
struct ElementDet {
  Bernstein<D> n;
  Bernstein<D> w;
};

template <int D>
ElementDet<D> element_det(const BezierElement<D>& e) {
  const int st = e.stride(), rows = e.rational ? D + 1 : D, first_deriv = e.rational ? 1 : 0;
  int npts = 1;
  for (int k = 0; k < D; ++k) npts *= e.degrees[k] + 1;
  std::vector<std::vector<Bernstein<D>>> m(rows, std::vector<Bernstein<D>>(rows));
  for (int r = 0; r < rows; ++r) {
    // The weight row first: det[(w, w x), d(w, w x)] = w^(D+1) det J with this order.
    const int c = e.rational ? (r == 0 ? D : r - 1) : r;
    std::vector<double> v(npts);
    for (int q = 0; q < npts; ++q) v[q] = e.coefs[static_cast<std::size_t>(q) * st + c];
    const Bernstein<D> f(e.degrees, std::move(v));
    for (int k = 0; k < D; ++k) {
      m[r][first_deriv + k] = f.derivative(k);
      m[r][first_deriv + k] *= 1.0 / e.domain.extent(k);
    }
    if (e.rational) m[r][0] = f;
  }
  ElementDet<D> out;
  out.n = determinant(m);
  if (e.rational) out.w = m[0][0];
  return out;
}

// A sub-box [lo, hi] (element-local coordinates in [0,1]^D) with the pieces of N and w on it.
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
    ElementDet<D> det = element_det(e_);
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
    return res_;
  }

private:
  // Lower bound of det J on the piece, and its corner values offered as the element minimum.
  void settle(Piece<D>& p) {
    const double nlo = p.n.min_coef();
    if (e_.rational) {
      const double wlo = p.w.min_coef(), whi = p.w.max_coef();
      p.lower = nlo >= 0 ? nlo / std::pow(whi, D + 1) : nlo / std::pow(wlo, D + 1);
    } else {
      p.lower = nlo;
    }
    for (int c = 0; c < (1 << D); ++c) {
      double v = p.n.corner(c);
      if (e_.rational) v /= std::pow(p.w.corner(c), D + 1);
      if (v < res_.value) {
        res_.value = v;
        for (int k = 0; k < D; ++k) {
          const double t = (c >> k) & 1 ? p.hi[k] : p.lo[k];
          res_.where[k] = (1.0 - t) * e_.domain.lo[k] + t * e_.domain.hi[k];
        }
      }
    }
  }

  // The direction in which the bound is loosest: relative coefficient variation of N, plus that of w
  // weighted by the power D+1 it enters det J with.
  int split_direction(const Piece<D>& p) const {
    const double scale = std::max(std::abs(p.n.min_coef()), std::abs(p.n.max_coef()));
    const double wlo = e_.rational ? p.w.min_coef() : 1.0;
    int best = 0;
    double best_score = -1;
    for (int k = 0; k < D; ++k) {
      double score = scale > 0 ? p.n.variation(k) / scale : 0.0;
      if (e_.rational) score += (D + 1) * p.w.variation(k) / wlo;
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
