#include "trivar/model/line_flux.hpp"

#include <algorithm>

#include "trivar/core/error.hpp"
#include "trivar/spline/basis.hpp"

namespace trivar {

LineFlux::LineFlux(const TensorSpline<2>& s, int dir, const QuadratureRule& rule) : s_(s), rule_(rule), dir_(dir) {
  require(s.dim() == 3, "line flux: the surface must have control dimension 3");
  const KnotVector& kr = s.knots(dir);
  const int w = kr.degree() + 1;
  const std::size_t nq = rule.nodes.size();
  breaks_ = kr.breakpoints();
  span_.resize(breaks_.size() - 1);
  table_.resize(span_.size() * nq * 2 * static_cast<std::size_t>(w));
  for (std::size_t k = 0; k < span_.size(); ++k) {
    span_[k] = kr.find_span(0.5 * (breaks_[k] + breaks_[k + 1]));
    const double a = breaks_[k], b = breaks_[k + 1];
    for (std::size_t q = 0; q < nq; ++q) {
      double* N = table_.data() + (k * nq + q) * 2 * static_cast<std::size_t>(w);
      basis_values_first_derivatives(kr, span_[k], a + rule.nodes[q] * (b - a), N, N + w);
    }
  }
}

template <int P, bool kRational, class Acc>
void LineFlux::sum(double t, double lo, double hi, const Acc& add) const {
  constexpr int st = kRational ? 4 : 3;
  const KnotVector& kr = s_.knots(dir_);
  const KnotVector& kf = s_.knots(1 - dir_);
  const int p = P >= 0 ? P : kr.degree(), w = p + 1;
  // The break intervals k0..k1 that can meet (lo, hi).
  const std::ptrdiff_t last = static_cast<std::ptrdiff_t>(span_.size()) - 1;
  const std::ptrdiff_t k0 = std::clamp<std::ptrdiff_t>(std::upper_bound(breaks_.begin(), breaks_.end(), lo) - breaks_.begin() - 1, 0, last);
  const std::ptrdiff_t k1 = std::clamp<std::ptrdiff_t>(std::lower_bound(breaks_.begin(), breaks_.end(), hi) - breaks_.begin() - 1, 0, last);
  if (!(hi > lo) || k1 < k0) return;

  // Contract the fixed direction: the homogeneous control values of the line's points and cross derivatives.
  const double tc = std::clamp(t, kf.start(), kf.end());
  const int sf = kf.find_span(tc), qf = kf.degree();
  double Nf[kMaxDegree + 1], dNf[kMaxDegree + 1];
  basis_values_first_derivatives(kf, sf, tc, Nf, dNf);
  const int first = span_[static_cast<std::size_t>(k0)] - p, m = span_[static_cast<std::size_t>(k1)] - first + 1;
  points_.assign(static_cast<std::size_t>(m) * st, 0.0);
  cross_.assign(static_cast<std::size_t>(m) * st, 0.0);
  const double* coefs = s_.coefs().data();
  const std::ptrdiff_t n0 = s_.count(0);
  // Steps between neighbours along the running and the fixed direction in the control array.
  const std::ptrdiff_t run_step = (dir_ == 0 ? 1 : n0) * st, fix_step = (dir_ == 0 ? n0 : 1) * st;
  for (int a = 0; a < m; ++a) {
    const double* c = coefs + (first + a) * run_step + (sf - qf) * fix_step;
    double* pt = points_.data() + a * st;
    double* cr = cross_.data() + a * st;
    for (int b = 0; b <= qf; ++b, c += fix_step)
      for (int d = 0; d < st; ++d) {
        pt[d] += Nf[b] * c[d];
        cr[d] += dNf[b] * c[d];
      }
  }

  const std::size_t nq = rule_.nodes.size();
  for (std::ptrdiff_t k = k0; k <= k1; ++k) {
    const std::size_t ks = static_cast<std::size_t>(k);
    const double a = std::max(breaks_[ks], lo), b = std::min(breaks_[ks + 1], hi);
    if (!(b > a)) continue;
    const bool whole = a == breaks_[ks] && b == breaks_[ks + 1];
    const double* P0 = points_.data() + static_cast<std::ptrdiff_t>(span_[ks] - p - first) * st;
    const double* C0 = cross_.data() + static_cast<std::ptrdiff_t>(span_[ks] - p - first) * st;
    for (std::size_t q = 0; q < nq; ++q) {
      double local[2 * (kMaxDegree + 1)];
      const double* N = local;
      if (whole)
        N = table_.data() + (ks * nq + q) * 2 * static_cast<std::size_t>(w);
      else
        basis_values_first_derivatives<P>(kr, span_[ks], a + rule_.nodes[q] * (b - a), local, local + w);
      const double* dN = N + w;
      double A[st] = {}, As[st] = {}, At[st] = {};  // point, running and fixed derivatives, homogeneous
      for (int r = 0; r < w; ++r)
        for (int d = 0; d < st; ++d) {
          A[d] += N[r] * P0[r * st + d];
          As[d] += dN[r] * P0[r * st + d];
          At[d] += N[r] * C0[r * st + d];
        }
      std::array<double, 3> S;
      double Ss[3], St[3];
      if constexpr (kRational) {
        const double inv = 1.0 / A[3];
        for (int d = 0; d < 3; ++d) {
          S[static_cast<std::size_t>(d)] = A[d] * inv;
          Ss[d] = (As[d] - As[3] * S[static_cast<std::size_t>(d)]) * inv;
          St[d] = (At[d] - At[3] * S[static_cast<std::size_t>(d)]) * inv;
        }
      } else {
        for (int d = 0; d < 3; ++d) {
          S[static_cast<std::size_t>(d)] = A[d];
          Ss[d] = As[d];
          St[d] = At[d];
        }
      }
      const double* Su = dir_ == 0 ? Ss : St;
      const double* Sv = dir_ == 0 ? St : Ss;
      const std::array<double, 3> n{Su[1] * Sv[2] - Su[2] * Sv[1], Su[2] * Sv[0] - Su[0] * Sv[2], Su[0] * Sv[1] - Su[1] * Sv[0]};
      add(rule_.weights[q] * (b - a), S, n);
    }
  }
}

template <class Acc>
void LineFlux::dispatch(double t, double lo, double hi, const Acc& add) const {
  const bool r = s_.is_rational();
  switch (s_.degree(dir_)) {
    case 1: return r ? sum<1, true>(t, lo, hi, add) : sum<1, false>(t, lo, hi, add);
    case 2: return r ? sum<2, true>(t, lo, hi, add) : sum<2, false>(t, lo, hi, add);
    case 3: return r ? sum<3, true>(t, lo, hi, add) : sum<3, false>(t, lo, hi, add);
    default: return r ? sum<-1, true>(t, lo, hi, add) : sum<-1, false>(t, lo, hi, add);
  }
}

// The accumulators see the weight, the point and the whole normal; they are inlined, so the normal components
// one does not read cost nothing.
double LineFlux::linear(double t, double lo, double hi, double shift) const {
  double sum = 0;
  dispatch(t, lo, hi, [&sum, shift](double w, const std::array<double, 3>& x, const std::array<double, 3>& n) { sum += w * ((x[0] - shift) * n[0]); });
  return sum;
}

double LineFlux::general(double t, double lo, double hi, const std::function<double(const std::array<double, 3>&)>& F) const {
  double sum = 0;
  dispatch(t, lo, hi, [&sum, &F](double w, const std::array<double, 3>& x, const std::array<double, 3>& n) { sum += w * (F(x) * n[0]); });
  return sum;
}

std::array<double, 3> LineFlux::area(double t, double lo, double hi) const {
  std::array<double, 3> sum{};
  dispatch(t, lo, hi, [&sum](double w, const std::array<double, 3>&, const std::array<double, 3>& n) {
    for (std::size_t k = 0; k < 3; ++k) sum[k] += w * n[k];
  });
  return sum;
}

}  // namespace trivar
