#include "trivar/spline/bezier_extraction.hpp"

#include <algorithm>

#include "trivar/spline/derivative_index.hpp"
#include "trivar/spline/knot_refinement.hpp"
#include "trivar/spline/tensor_map.hpp"

namespace trivar {

namespace {

// The knot vector in which every breakpoint of the domain has multiplicity >= p: its B-splines restricted to
// an element are exactly that element's Bernstein polynomials.
KnotVector bezier_knots(const KnotVector& kv) {
  std::vector<double> t = kv.knots();
  const int p = kv.degree();
  for (double b : kv.breakpoints())
    for (int m = kv.multiplicity(b); m < p; ++m) t.insert(std::upper_bound(t.begin(), t.end(), b), b);
  return KnotVector(p, std::move(t));
}

}  // namespace

std::vector<ElementExtraction> extraction_operators(const KnotVector& kv) {
  const int p = kv.degree();
  const KnotVector to = bezier_knots(kv);
  const SparseRowMatrix R = refinement_matrix(kv, to);
  const Eigen::MatrixXd Rd(R);
  const std::vector<double> bp = kv.breakpoints();
  std::vector<ElementExtraction> out;
  for (std::size_t e = 0; e + 1 < bp.size(); ++e) {
    ElementExtraction x;
    x.lo = bp[e];
    x.hi = bp[e + 1];
    const int s_old = kv.find_span(x.lo), s_new = to.find_span(x.lo);
    x.first = s_old - p;
    x.C = Rd.block(s_new - p, s_old - p, p + 1, p + 1).transpose();
    out.push_back(std::move(x));
  }
  return out;
}

template <int D>
std::vector<BezierElement<D>> bezier_elements(const TensorSpline<D>& s) {
  // Refine to Bezier form once, then cut the control net into element blocks.
  TensorSpline<D> b = s;
  std::array<std::vector<double>, D> bps;
  std::array<int, D> ne;
  for (int k = 0; k < D; ++k) {
    KnotVector to = bezier_knots(s.knots(k));
    b = apply_along(b, k, to, refinement_matrix(s.knots(k), to));
    bps[k] = s.knots(k).breakpoints();
    ne[k] = static_cast<int>(bps[k].size()) - 1;
  }
  int total = 1;
  for (int k = 0; k < D; ++k) total *= ne[k];
  std::vector<BezierElement<D>> out(total);
  const int st = s.stride();
  for (int e = 0; e < total; ++e) {
    BezierElement<D>& el = out[e];
    std::array<int, D> ei, first, len;
    int r = e, npts = 1;
    for (int k = 0; k < D; ++k) {
      ei[k] = r % ne[k];
      r /= ne[k];
      el.domain.lo[k] = bps[k][ei[k]];
      el.domain.hi[k] = bps[k][ei[k] + 1];
      el.degrees[k] = s.degree(k);
      first[k] = b.knots(k).find_span(el.domain.lo[k]) - s.degree(k);
      len[k] = s.degree(k) + 1;
      npts *= len[k];
    }
    el.dim = s.dim();
    el.rational = s.is_rational();
    el.coefs.resize(static_cast<std::size_t>(npts) * st);
    for (int q = 0; q < npts; ++q) {
      typename TensorSpline<D>::Index gi;
      int rr = q;
      for (int k = 0; k < D; ++k) {
        gi[k] = first[k] + rr % len[k];
        rr /= len[k];
      }
      const double* c = b.coef(b.linear_index(gi));
      std::copy(c, c + st, el.coefs.begin() + static_cast<std::ptrdiff_t>(q) * st);
    }
  }
  return out;
}

template <int D>
void eval_bezier(const BezierElement<D>& e, const Param<D>& u, double* out) {
  // Bernstein values per direction, then the tensor sum.
  std::array<std::vector<double>, D> B;
  for (int k = 0; k < D; ++k) {
    const int p = e.degrees[k];
    const double t = (u[k] - e.domain.lo[k]) / (e.domain.hi[k] - e.domain.lo[k]);
    B[k].resize(p + 1);
    for (int i = 0; i <= p; ++i)
      B[k][i] = static_cast<double>(binomial(p, i)) * std::pow(t, i) * std::pow(1.0 - t, p - i);
  }
  const int st = e.stride();
  std::vector<double> acc(st, 0.0);
  int npts = 1;
  for (int k = 0; k < D; ++k) npts *= e.degrees[k] + 1;
  for (int q = 0; q < npts; ++q) {
    double w = 1.0;
    int r = q;
    for (int k = 0; k < D; ++k) {
      w *= B[k][r % (e.degrees[k] + 1)];
      r /= e.degrees[k] + 1;
    }
    for (int d = 0; d < st; ++d) acc[d] += w * e.coefs[static_cast<std::size_t>(q) * st + d];
  }
  for (int d = 0; d < e.dim; ++d) out[d] = e.rational ? acc[d] / acc[e.dim] : acc[d];
}

#define TRIVAR_INSTANTIATE(D)                                                        \
  template std::vector<BezierElement<D>> bezier_elements(const TensorSpline<D>&); \
  template void eval_bezier(const BezierElement<D>&, const Param<D>&, double*);
TRIVAR_INSTANTIATE(1)
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

}  // namespace trivar
