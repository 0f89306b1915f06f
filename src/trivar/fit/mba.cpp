#include "trivar/fit/mba.hpp"

#include <vector>

#include <Eigen/Core>

#include "trivar/core/error.hpp"
#include "trivar/core/parallel.hpp"
#include "trivar/fit/element_bernstein.hpp"
#include "trivar/lr/lr_bezier_extraction.hpp"

namespace trivar {
namespace mba_detail {

// Per element: for each of its B-splines the sums sum_i w^3 r_i / sum_k w_k^2 (dim values) and sum_i w^2.
template <int D, int P>
void accumulate_wishes(const Ints<D>& deg, const Box<D>& box, const Eigen::MatrixXd& C, const ScatteredData<D>& data,
                       std::span<const int> points, std::span<const double> residuals, double* num, double* den) {
  // C row by row with the Bernstein count known at compile time where the degrees are: a plain loop the compiler
  // unrolls (Eigen's general matrix-vector product took a fifth of the fit's time here).
  const int nb = static_cast<int>(C.cols());
  constexpr int NB = P >= 0 ? [] {
    int n = 1;
    for (int k = 0; k < D; ++k) n *= P + 1;
    return n;
  }() : 0;
  const int cols = NB > 0 ? NB : nb;
  const auto nids = C.rows();
  const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows = C;
  const Param<D> inv_h = fit_kernel::reciprocal_sides(box);
  const int m = data.dim;
  double b[256];
  std::vector<double> w(static_cast<std::size_t>(nids));  // an LR element may carry more than (p + 1)^D B-splines
  for (int i : points) {
    fit_kernel::tensor_bernstein<D, P>(deg, box.lo, inv_h, data.params[static_cast<std::size_t>(i)], b);
    double s = 0.0;
    for (Eigen::Index j = 0; j < nids; ++j) {
      const double* c = rows.data() + j * cols;
      double v = 0.0;
      for (int q = 0; q < cols; ++q) v += c[q] * b[q];
      w[static_cast<std::size_t>(j)] = v;
      s += v * v;
    }
    if (!(s > 0.0)) continue;
    const double inv_s = 1.0 / s;
    const double* r = residuals.data() + static_cast<std::size_t>(i) * static_cast<std::size_t>(m);
    for (Eigen::Index j = 0; j < nids; ++j) {
      const double wj = w[static_cast<std::size_t>(j)], w2 = wj * wj;
      den[j] += w2;
      const double f = w2 * wj * inv_s;
      for (int c = 0; c < m; ++c) num[j * m + c] += f * r[c];
    }
  }
}

// Subtracts the correction's Bezier net (nb x m, column-major) at each point of the element from its residual.
template <int D, int P>
void subtract_correction(const Ints<D>& deg, const Box<D>& box, const double* net, int nb, const ScatteredData<D>& data,
                         std::span<const int> points, std::span<double> residuals) {
  const Param<D> inv_h = fit_kernel::reciprocal_sides(box);
  const int m = data.dim;
  double b[256];
  for (int i : points) {
    fit_kernel::tensor_bernstein<D, P>(deg, box.lo, inv_h, data.params[static_cast<std::size_t>(i)], b);
    double* r = residuals.data() + static_cast<std::size_t>(i) * static_cast<std::size_t>(m);
    for (int c = 0; c < m; ++c) {
      double v = 0.0;
      for (int q = 0; q < nb; ++q) v += net[c * nb + q] * b[q];
      r[c] -= v;
    }
  }
}

}  // namespace mba_detail

template <int D>
void mba_update(const LRSpline<D>& lr, const ScatteredData<D>& data, const PointsByElement& where,
                std::span<double> coefs, std::span<double> residuals, int passes, int threads) {
  require(passes >= 1, "fit: MBA needs at least one pass");
  const int m = data.dim;
  const int n = lr.num_basis();
  const int ne = lr.num_elements();
  require(coefs.size() == static_cast<std::size_t>(n) * static_cast<std::size_t>(m) &&
              residuals.size() == data.size() * static_cast<std::size_t>(m),
          "fit: MBA needs " + std::to_string(n) + " x " + std::to_string(m) + " coefficients and " +
              std::to_string(data.size()) + " x " + std::to_string(m) + " residuals");
  const Ints<D>& deg = lr.degrees();
  int nb = 1;
  for (int k = 0; k < D; ++k) nb *= deg[k] + 1;
  // Per element one block: nids * m wishes, then nids weights (summed per B-spline after the parallel loop).
  std::vector<std::size_t> start(static_cast<std::size_t>(ne) + 1, 0);
  for (int e = 0; e < ne; ++e)
    start[static_cast<std::size_t>(e) + 1] =
        start[static_cast<std::size_t>(e)] + lr.element_support(e).size() * static_cast<std::size_t>(m + 1);
  // The elements' extraction operators, built once for all sweeps of all passes while they take at most 256 MB
  // (a quarter of MBA's instructions at 10^5 points went into rebuilding them), else rebuilt per sweep.
  double cache_bytes = 0.0;
  for (int e = 0; e < ne; ++e)
    if (!fit_kernel::points_of(where, e).empty())
      cache_bytes += 8.0 * static_cast<double>(lr.element_support(e).size()) * nb;
  const bool cached = cache_bytes <= 256e6;
  std::vector<Eigen::MatrixXd> operators(cached ? static_cast<std::size_t>(ne) : 0);
  // Each element is visited by one thread per loop, so filling its slot on first use does not race.
  const auto extraction = [&](int e, Eigen::MatrixXd& scratch) -> const Eigen::MatrixXd& {
    Eigen::MatrixXd& C = cached ? operators[static_cast<std::size_t>(e)] : scratch;
    if (!cached || C.size() == 0) C = extraction_operator(deg, lr.basis_functions(), lr.element_support(e), lr.element(e));
    return C;
  };
  // Both halves of a pass visit the elements that hold points, with their support and extraction operator.
  const auto for_each_element_with_points = [&](auto&& body) {
    parallel_for(ne, threads, [&](std::ptrdiff_t ei) {
      const int e = static_cast<int>(ei);
      const std::span<const int> pts = fit_kernel::points_of(where, e);
      if (pts.empty()) return;
      Eigen::MatrixXd scratch;
      body(e, pts, lr.element(e), lr.element_support(e), extraction(e, scratch));
    });
  };
  std::vector<double> local(start.back());
  std::vector<double> num(static_cast<std::size_t>(n) * static_cast<std::size_t>(m)), den(static_cast<std::size_t>(n));
  for (int pass = 0; pass < passes; ++pass) {
    std::fill(local.begin(), local.end(), 0.0);
    for_each_element_with_points([&](int e, std::span<const int> pts, const Box<D>& box, std::span<const int> ids,
                                     const Eigen::MatrixXd& C) {
      double* wishes = local.data() + start[static_cast<std::size_t>(e)];
      double* weights = wishes + ids.size() * static_cast<std::size_t>(m);
      fit_kernel::with_degree<D>(deg, [&](auto P) {
        mba_detail::accumulate_wishes<D, P()>(deg, box, C, data, pts, residuals, wishes, weights);
      });
    });
    std::fill(num.begin(), num.end(), 0.0);
    std::fill(den.begin(), den.end(), 0.0);
    for (int e = 0; e < ne; ++e) {
      const std::span<const int> ids = lr.element_support(e);
      const double* a = local.data() + start[static_cast<std::size_t>(e)];
      const double* w = a + ids.size() * static_cast<std::size_t>(m);
      for (std::size_t r = 0; r < ids.size(); ++r) {
        const auto id = static_cast<std::size_t>(ids[r]);
        den[id] += w[r];
        for (int c = 0; c < m; ++c) num[id * static_cast<std::size_t>(m) + static_cast<std::size_t>(c)] += a[r * static_cast<std::size_t>(m) + static_cast<std::size_t>(c)];
      }
    }
    // delta_j in num; B-splines without points keep their coefficient.
    for (std::size_t j = 0; j < den.size(); ++j)
      for (int c = 0; c < m; ++c) {
        double& d = num[j * static_cast<std::size_t>(m) + static_cast<std::size_t>(c)];
        d = den[j] > 0.0 ? d / den[j] : 0.0;
        coefs[j * static_cast<std::size_t>(m) + static_cast<std::size_t>(c)] += d;
      }
    for_each_element_with_points([&](int, std::span<const int> pts, const Box<D>& box, std::span<const int> ids,
                                     const Eigen::MatrixXd& C) {
      Eigen::MatrixXd delta(static_cast<Eigen::Index>(ids.size()), m);
      for (std::size_t r = 0; r < ids.size(); ++r)
        for (int c = 0; c < m; ++c)
          delta(static_cast<Eigen::Index>(r), c) = num[static_cast<std::size_t>(ids[r]) * static_cast<std::size_t>(m) + static_cast<std::size_t>(c)];
      const Eigen::MatrixXd net = C.transpose() * delta;  // nb x m
      fit_kernel::with_degree<D>(deg, [&](auto P) {
        mba_detail::subtract_correction<D, P()>(deg, box, net.data(), nb, data, pts, residuals);
      });
    });
  }
}

template void mba_update(const LRSpline<2>&, const ScatteredData<2>&, const PointsByElement&, std::span<double>,
                         std::span<double>, int, int);
template void mba_update(const LRSpline<3>&, const ScatteredData<3>&, const PointsByElement&, std::span<double>,
                         std::span<double>, int, int);

}  // namespace trivar
