#include "trivar/tspline/t_spline_surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "trivar/core/error.hpp"
#include "trivar/core/memory_budget.hpp"
#include "trivar/core/parallel.hpp"
#include "trivar/spline/basis.hpp"
#include "trivar/tspline/local_knots.hpp"

namespace trivar {

namespace {

// Bernstein values of degree p at x in [0, 1] (b[0..p]), and with kDerivatives their derivatives with respect
// to the element parameter (scale 1/h) in db.
template <bool kDerivatives>
inline void bernstein(int p, double x, double inv_h, double* b, double* db) {
  const double y = 1.0 - x;
  b[0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    if (kDerivatives && j == p) {
      db[0] = -p * b[0] * inv_h;
      for (int i = 1; i < p; ++i) db[i] = p * (b[i - 1] - b[i]) * inv_h;
      db[p] = p * b[p - 1] * inv_h;
    }
    b[j] = x * b[j - 1];
    for (int i = j - 1; i >= 1; --i) b[i] = y * b[i] + x * b[i - 1];
    b[0] *= y;
  }
  if (kDerivatives && p == 0) db[0] = 0.0;
}

}  // namespace

TSplineSurface::TSplineSurface(const TSpline& ts, int threads) : degrees_(ts.degrees), basis_(blending_functions(ts)) {
  std::vector<Box<2>> faces;
  for (int f = 0; f < static_cast<int>(ts.image.faces.size()); ++f) faces.push_back(ts.image.face_box(f));
  build(faces, threads);
}

TSplineSurface::TSplineSurface(const TSpline& ts, const std::vector<Box<2>>& regions, int threads)
    : degrees_(ts.degrees), basis_(blending_functions(ts)) {
  build(regions, threads);
}

TSplineSurface::TSplineSurface(const Ints<2>& degrees, std::vector<LRBSpline<2>> basis, int threads)
    : degrees_(degrees), basis_(std::move(basis)) {
  require(!basis_.empty(), "T-spline: no blending function");
  std::vector<Box<2>> supports;
  for (std::size_t i = 0; i < basis_.size(); ++i) {
    const LRBSpline<2>& b = basis_[i];
    for (int k = 0; k < 2; ++k) {
      const auto& t = b.knots[static_cast<std::size_t>(k)];
      require(degrees_[k] >= 1 && degrees_[k] <= kMaxDegree && static_cast<int>(t.size()) == degrees_[k] + 2 &&
                  std::is_sorted(t.begin(), t.end()) && t.front() < t.back(),
              [&] { return "T-spline: blending function " + std::to_string(i) + " has invalid local knots"; });
    }
    require(b.coef.size() == 4 && b.coef[3] > 0,
            [&] { return "T-spline: blending function " + std::to_string(i) + " needs (w x, w y, w z, w) with w > 0"; });
    supports.push_back(b.support());
  }
  build(supports, threads);
}

void TSplineSurface::build(const std::vector<Box<2>>& regions, int threads) {
  for (const LRBSpline<2>& b : basis_)
    for (int k = 0; k < 2; ++k) lines_[k].insert(lines_[k].end(), b.knots[k].begin(), b.knots[k].end());
  for (int k = 0; k < 2; ++k) {
    std::sort(lines_[k].begin(), lines_[k].end());
    lines_[k].erase(std::unique(lines_[k].begin(), lines_[k].end()), lines_[k].end());
    require(lines_[k].size() >= 2, "T-spline: no knot interval in direction " + std::string(k == 0 ? "s" : "t"));
    domain_.lo[k] = lines_[k].front();
    domain_.hi[k] = lines_[k].back();
  }
  const std::size_t nu = lines_[0].size() - 1, nv = lines_[1].size() - 1;
  // The cell grid (and a Bezier net per covered cell) grows with the product of the distinct knot counts.
  const int P = (degrees_[0] + 1) * (degrees_[1] + 1);
  require_memory(static_cast<double>(nu) * static_cast<double>(nv) * (5.0 + 32.0 * P),
                 "T-spline Bezier elements on a " + std::to_string(nu) + " x " + std::to_string(nv) + " knot grid");
  cell_element_.assign(nu * nv, -1);
  std::vector<char> covered(nu * nv, 0);
  for (const Box<2>& b : regions) {
    std::array<std::size_t, 2> lo, hi;
    for (int k = 0; k < 2; ++k) {
      lo[k] = static_cast<std::size_t>(std::lower_bound(lines_[k].begin(), lines_[k].end(), b.lo[k]) - lines_[k].begin());
      hi[k] = static_cast<std::size_t>(std::lower_bound(lines_[k].begin(), lines_[k].end(), b.hi[k]) - lines_[k].begin());
    }
    for (std::size_t j = lo[1]; j < hi[1]; ++j)
      for (std::size_t i = lo[0]; i < hi[0]; ++i) covered[i + nu * j] = 1;
  }
  for (std::size_t c = 0; c < nu * nv; ++c)
    if (covered[c]) {
      const std::size_t i = c % nu, j = c / nu;
      cell_element_[c] = static_cast<int>(elements_.size());
      elements_.push_back(Box<2>{{lines_[0][i], lines_[1][j]}, {lines_[0][i + 1], lines_[1][j + 1]}});
    }
  require(!elements_.empty(), "T-spline: no face");
  supports_ = trivar::element_supports<2>(basis_, elements_, threads);

  // One extraction operator per element gives both the Bezier net and the partition-of-unity coefficients.
  bezier_.resize(elements_.size());
  std::vector<PartitionOfUnity> per(elements_.size());
  parallel_for(static_cast<std::ptrdiff_t>(elements_.size()), threads, [&](std::ptrdiff_t e) {
    const auto ids = supports_[static_cast<int>(e)];
    BezierElement<2>& z = bezier_[static_cast<std::size_t>(e)];
    z.domain = elements_[static_cast<std::size_t>(e)];
    z.degrees = degrees_;
    z.dim = 3;
    z.rational = true;
    z.coefs.assign(static_cast<std::size_t>(P) * 4, 0.0);
    PartitionOfUnity& pu = per[static_cast<std::size_t>(e)];
    if (ids.empty()) {
      pu = {0, 0, 1, 1};
      return;
    }
    const Eigen::MatrixXd C = extraction_operator<2>(degrees_, basis_, ids, z.domain);
    pu.min_sum = pu.sampled_min = std::numeric_limits<double>::infinity();
    pu.max_sum = pu.sampled_max = -pu.min_sum;
    std::vector<double> sums(static_cast<std::size_t>(P));
    for (int j = 0; j < P; ++j) {
      double sum = 0;
      for (int r = 0; r < static_cast<int>(ids.size()); ++r) {
        const double c = C(r, j);
        sum += c;
        const auto& coef = basis_[static_cast<std::size_t>(ids[static_cast<std::size_t>(r)])].coef;
        for (int d = 0; d < 4; ++d) z.coefs[static_cast<std::size_t>(j) * 4 + d] += c * coef[static_cast<std::size_t>(d)];
      }
      sums[static_cast<std::size_t>(j)] = sum;
      pu.min_sum = std::min(pu.min_sum, sum);
      pu.max_sum = std::max(pu.max_sum, sum);
      pu.max_defect = std::max(pu.max_defect, std::abs(sum - 1.0));
    }
    pu.elements_off = pu.max_defect > 1e-12 ? 1 : 0;
    const int p = degrees_[0], q = degrees_[1];
    double bs[kMaxDegree + 1], bt[kMaxDegree + 1];
    for (int b = 0; b < 5; ++b)
      for (int a = 0; a < 5; ++a) {
        bernstein<false>(p, 0.25 * a, 1.0, bs, nullptr);
        bernstein<false>(q, 0.25 * b, 1.0, bt, nullptr);
        double v = 0;
        for (int j = 0; j <= q; ++j)
          for (int i = 0; i <= p; ++i) v += bs[i] * bt[j] * sums[static_cast<std::size_t>(i + (p + 1) * j)];
        pu.sampled_min = std::min(pu.sampled_min, v);
        pu.sampled_max = std::max(pu.sampled_max, v);
      }
  });
  pu_.min_sum = pu_.sampled_min = std::numeric_limits<double>::infinity();
  pu_.max_sum = pu_.sampled_max = -pu_.min_sum;
  for (const PartitionOfUnity& p : per) {
    pu_.min_sum = std::min(pu_.min_sum, p.min_sum);
    pu_.max_sum = std::max(pu_.max_sum, p.max_sum);
    pu_.max_defect = std::max(pu_.max_defect, p.max_defect);
    pu_.sampled_min = std::min(pu_.sampled_min, p.sampled_min);
    pu_.sampled_max = std::max(pu_.sampled_max, p.sampled_max);
    pu_.elements_off += p.elements_off;
  }
}

int TSplineSurface::locate(const Param<2>& u) const {
  std::array<std::size_t, 2> c;
  for (int k = 0; k < 2; ++k) {
    const auto& L = lines_[k];
    if (!(u[k] >= L.front() && u[k] <= L.back())) return -1;
    const std::size_t i = static_cast<std::size_t>(std::upper_bound(L.begin(), L.end(), u[k]) - L.begin());
    c[k] = std::min(i, L.size() - 1) - 1;
  }
  return cell_element_[c[0] + (lines_[0].size() - 1) * c[1]];
}


template <bool kDerivatives>
void TSplineSurface::eval_element(int e, const Param<2>& u, double* out) const {
  if (e < 0) {
    std::fill(out, out + (kDerivatives ? 9 : 3), std::numeric_limits<double>::quiet_NaN());
    return;
  }
  const BezierElement<2>& z = bezier_[static_cast<std::size_t>(e)];
  const int p = degrees_[0], q = degrees_[1];
  double bs[kMaxDegree + 1], bt[kMaxDegree + 1], dbs[kMaxDegree + 1], dbt[kMaxDegree + 1];
  const double hs = 1.0 / z.domain.extent(0), ht = 1.0 / z.domain.extent(1);
  bernstein<kDerivatives>(p, (u[0] - z.domain.lo[0]) * hs, hs, bs, dbs);
  bernstein<kDerivatives>(q, (u[1] - z.domain.lo[1]) * ht, ht, bt, dbt);
  double a[4] = {0, 0, 0, 0}, as[4] = {0, 0, 0, 0}, at[4] = {0, 0, 0, 0};
  const double* c = z.coefs.data();
  for (int j = 0; j <= q; ++j) {
    double row[4] = {0, 0, 0, 0}, drow[4] = {0, 0, 0, 0};
    for (int i = 0; i <= p; ++i, c += 4)
      for (int d = 0; d < 4; ++d) {
        row[d] += bs[i] * c[d];
        if constexpr (kDerivatives) drow[d] += dbs[i] * c[d];
      }
    for (int d = 0; d < 4; ++d) {
      a[d] += bt[j] * row[d];
      if constexpr (kDerivatives) {
        as[d] += bt[j] * drow[d];
        at[d] += dbt[j] * row[d];
      }
    }
  }
  const double iw = 1.0 / a[3];
  for (int d = 0; d < 3; ++d) out[d] = a[d] * iw;
  if constexpr (kDerivatives)
    for (int d = 0; d < 3; ++d) {
      out[3 + d] = (as[d] - out[d] * as[3]) * iw;
      out[6 + d] = (at[d] - out[d] * at[3]) * iw;
    }
}

void TSplineSurface::eval(const Param<2>& u, double* out) const { eval_impl<false>(u, out); }
void TSplineSurface::eval_on_element(int e, const Param<2>& u, double* out) const {
  require(e >= 0 && e < static_cast<int>(elements_.size()), "TSplineSurface::eval_on_element: no element " + std::to_string(e));
  eval_element<false>(e, u, out);
}

void TSplineSurface::eval_first_derivatives_on_element(int e, const Param<2>& u, double* out) const {
  require(e >= 0 && e < static_cast<int>(elements_.size()), "TSplineSurface::eval_first_derivatives_on_element: no element " + std::to_string(e));
  eval_element<true>(e, u, out);
}
void TSplineSurface::eval_first_derivatives(const Param<2>& u, double* out) const { eval_impl<true>(u, out); }

void TSplineSurface::eval_many(std::span<const Param<2>> u, std::span<double> out, int threads) const {
  require(out.size() == u.size() * 3, "TSplineSurface::eval_many: output size must be 3 per point");
  parallel_for(static_cast<std::ptrdiff_t>(u.size()), threads,
               [&](std::ptrdiff_t i) { eval_impl<false>(u[static_cast<std::size_t>(i)], out.data() + 3 * i); });
}

}  // namespace trivar
