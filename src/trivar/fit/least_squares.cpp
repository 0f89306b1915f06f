#include "trivar/fit/least_squares.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "trivar/core/error.hpp"
#include "trivar/core/gauss_legendre.hpp"
#include "trivar/core/memory_budget.hpp"
#include "trivar/core/parallel.hpp"
#include "trivar/fit/element_bernstein.hpp"
#include "trivar/iga/solver.hpp"
#include "trivar/lr/lr_bezier_extraction.hpp"
#include "trivar/spline/basis.hpp"

namespace trivar {
namespace {

using fit_kernel::points_of;
using fit_kernel::tensor_bernstein;
using fit_kernel::with_degree;

// Bernstein values of degree q at t with their first and second derivatives in t (q >= 0).
void bernstein_with_derivatives(int p, double t, double* B, double* d1, double* d2) {
  double lower[kMaxDegree + 3] = {};
  bernstein_values<-1>(p, t, 1.0, B, nullptr);
  // d/dt B_{i,p} = p (B_{i-1,p-1} - B_{i,p-1}), applied twice (terms outside 0..q are zero).
  std::fill(d1, d1 + p + 1, 0.0);
  std::fill(d2, d2 + p + 1, 0.0);
  if (p >= 1) {
    bernstein_values<-1>(p - 1, t, 1.0, lower, nullptr);
    for (int i = 0; i <= p; ++i) d1[i] = p * ((i > 0 ? lower[i - 1] : 0.0) - (i < p ? lower[i] : 0.0));
  }
  if (p >= 2) {
    bernstein_values<-1>(p - 2, t, 1.0, lower, nullptr);
    auto at = [&](int j) { return j >= 0 && j <= p - 2 ? lower[j] : 0.0; };
    for (int i = 0; i <= p; ++i) d2[i] = p * (p - 1) * (at(i - 2) - 2.0 * at(i - 1) + at(i));
  }
}

// Gram matrices on [0, 1] of the degree-p Bernstein polynomials' derivatives of order 0, 1, 2.
struct BernsteinGram {
  std::array<Eigen::MatrixXd, 3> m;
  explicit BernsteinGram(int p) {
    const QuadratureRule q = gauss_legendre(p + 1);
    for (auto& x : m) x = Eigen::MatrixXd::Zero(p + 1, p + 1);
    std::vector<double> v(3 * static_cast<std::size_t>(p + 1));
    for (std::size_t g = 0; g < q.nodes.size(); ++g) {
      bernstein_with_derivatives(p, q.nodes[g], v.data(), v.data() + p + 1, v.data() + 2 * (p + 1));
      for (int r = 0; r < 3; ++r) {
        const Eigen::Map<const Eigen::VectorXd> b(v.data() + r * (p + 1), p + 1);
        m[static_cast<std::size_t>(r)].noalias() += q.weights[g] * b * b.transpose();
      }
    }
  }
};

// Kronecker product of per-direction matrices, direction 0 fastest (the Bernstein order of the extraction).
template <int D>
Eigen::MatrixXd kron(const std::array<const Eigen::MatrixXd*, D>& f) {
  Eigen::MatrixXd r = *f[0];
  for (int k = 1; k < D; ++k) {
    const Eigen::MatrixXd& a = *f[k];
    Eigen::MatrixXd n(r.rows() * a.rows(), r.cols() * a.cols());
    for (Eigen::Index i = 0; i < a.rows(); ++i)
      for (Eigen::Index j = 0; j < a.cols(); ++j) n.block(i * r.rows(), j * r.cols(), r.rows(), r.cols()) = a(i, j) * r;
    r = std::move(n);
  }
  return r;
}

// The thin-plate energy of a polynomial on an element with sides h, in its tensor Bernstein basis: for every pair
// j <= k the Gram matrix of d^2/du_j du_k (twice for j != k), from the unit-interval matrices by the chain rule.
template <int D>
Eigen::MatrixXd element_energy(const std::array<BernsteinGram, D>& gram, const Param<D>& h) {
  double vol = 1.0;
  for (int k = 0; k < D; ++k) vol *= h[k];
  Eigen::MatrixXd K;
  for (int j = 0; j < D; ++j)
    for (int k = j; k < D; ++k) {
      std::array<const Eigen::MatrixXd*, D> f;
      for (int l = 0; l < D; ++l) {
        const int order = (l == j) + (l == k);
        f[l] = &gram[l].m[static_cast<std::size_t>(order)];
      }
      const double s = (j == k ? 1.0 : 2.0) * vol / (h[j] * h[j] * h[k] * h[k]);
      Eigen::MatrixXd term = kron<D>(f) * s;
      if (K.size() == 0) K = std::move(term);
      else K += term;
    }
  return K;
}

// Bernstein Gram matrix (lower triangle of G, nb x nb column-major) and moments g (nb x m) of an element's points.
template <int D, int P>
void accumulate(const Ints<D>& deg, const Box<D>& box, const ScatteredData<D>& data, std::span<const int> points,
                double* G, double* g) {
  const int nb = [&] {
    int n = 1;
    for (int k = 0; k < D; ++k) n *= (P >= 0 ? P : deg[k]) + 1;
    return n;
  }();
  const Param<D> inv_h = fit_kernel::reciprocal_sides(box);
  double b[256];
  for (int i : points) {
    tensor_bernstein<D, P>(deg, box.lo, inv_h, data.params[static_cast<std::size_t>(i)], b);
    for (int c = 0; c < nb; ++c) {
      const double bc = b[c];
      double* col = G + c * nb;
      for (int r = c; r < nb; ++r) col[r] += b[r] * bc;
    }
    const double* f = data.value(static_cast<std::size_t>(i));
    for (int c = 0; c < data.dim; ++c)
      for (int r = 0; r < nb; ++r) g[c * nb + r] += f[c] * b[r];
  }
}

// The largest component error of every point of an element whose Bezier net (nb x m, column-major) is `net`.
template <int D, int P>
void element_errors(const Ints<D>& deg, const Box<D>& box, const ScatteredData<D>& data, std::span<const int> points,
                    const double* net, int nb, std::vector<double>& errors) {
  const Param<D> inv_h = fit_kernel::reciprocal_sides(box);
  double b[256];
  for (int i : points) {
    tensor_bernstein<D, P>(deg, box.lo, inv_h, data.params[static_cast<std::size_t>(i)], b);
    const double* f = data.value(static_cast<std::size_t>(i));
    double err = 0.0;
    for (int c = 0; c < data.dim; ++c) {
      double v = 0.0;
      for (int r = 0; r < nb; ++r) v += net[c * nb + r] * b[r];
      err = std::max(err, std::abs(v - f[c]));
    }
    errors[static_cast<std::size_t>(i)] = err;
  }
}

}  // namespace

template <int D>
PointsByElement locate_points(const LRSpline<D>& lr, std::span<const Param<D>> params, int threads) {
  const ElementEvaluator<D>& ev = lr.evaluator();
  std::vector<int> elem(params.size());
  parallel_for(static_cast<std::ptrdiff_t>(params.size()), threads,
               [&](std::ptrdiff_t i) { elem[static_cast<std::size_t>(i)] = ev.find_element(params[static_cast<std::size_t>(i)]); });
  PointsByElement r;
  r.offsets.assign(static_cast<std::size_t>(lr.num_elements()) + 1, 0);
  for (int e : elem) ++r.offsets[static_cast<std::size_t>(e) + 1];
  for (std::size_t e = 0; e + 1 < r.offsets.size(); ++e) r.offsets[e + 1] += r.offsets[e];
  r.points.resize(params.size());
  std::vector<int> fill(r.offsets.begin(), r.offsets.end() - 1);
  for (std::size_t i = 0; i < elem.size(); ++i) r.points[static_cast<std::size_t>(fill[static_cast<std::size_t>(elem[i])]++)] = static_cast<int>(i);
  return r;
}

template <int D>
LeastSquaresResult least_squares_fit(const LRSpline<D>& lr, const ScatteredData<D>& data, const PointsByElement& where,
                                     double smoothing, int threads) {
  require(smoothing >= 0.0 && std::isfinite(smoothing), "fit: the smoothing weight must be >= 0");
  const Ints<D>& deg = lr.degrees();
  const int m = data.dim;
  const int ne = lr.num_elements();
  for (int k = 0; k < D; ++k) require(deg[k] >= 1 && deg[k] <= 5, "fit: degree " + std::to_string(deg[k]) + " outside 1..5");
  int nb = 1;
  for (int k = 0; k < D; ++k) nb *= deg[k] + 1;
  const Box<D>& dom = lr.domain();
  double vol = 1.0;
  for (int k = 0; k < D; ++k) vol *= dom.hi[k] - dom.lo[k];
  const double L = std::pow(vol, 1.0 / D);
  const double w = smoothing * static_cast<double>(data.size()) * std::pow(L, 4) / vol;
  std::array<BernsteinGram, D> gram = [&]<std::size_t... I>(std::index_sequence<I...>) {
    return std::array<BernsteinGram, D>{BernsteinGram(deg[I])...};
  }(std::make_index_sequence<D>{});

  // Local systems, one block per element: nids^2 matrix entries then nids * m right-hand sides.
  std::vector<std::size_t> start(static_cast<std::size_t>(ne) + 1, 0);
  for (int e = 0; e < ne; ++e) {
    const std::size_t k = lr.element_support(e).size();
    start[static_cast<std::size_t>(e) + 1] = start[static_cast<std::size_t>(e)] + k * k + k * static_cast<std::size_t>(m);
  }
  // The local systems, the triplets of the global matrix (twice: Eigen sorts them into a copy) and the matrix.
  require_memory(8.0 * static_cast<double>(start.back()) + 40.0 * static_cast<double>(start.back()),
                 "fit: the least-squares system of " + std::to_string(lr.num_basis()) + " coefficients");
  std::vector<double> local(start.back());
  parallel_for(ne, threads, [&](std::ptrdiff_t ei) {
    const int e = static_cast<int>(ei);
    const Box<D>& box = lr.element(e);
    const std::span<const int> ids = lr.element_support(e);
    const Eigen::MatrixXd C = extraction_operator(deg, lr.basis_functions(), ids, box);
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(nb, nb);
    Eigen::MatrixXd g = Eigen::MatrixXd::Zero(nb, m);
    with_degree<D>(deg, [&](auto P) {
      accumulate<D, P()>(deg, box, data, points_of(where, e), G.data(), g.data());
    });
    G.template triangularView<Eigen::StrictlyUpper>() = G.transpose();
    if (w > 0.0) {
      Param<D> h;
      double ve = 1.0;
      for (int k = 0; k < D; ++k) ve *= h[k] = box.hi[k] - box.lo[k];
      G += (w * std::pow(ve, 2.0 / D) / (L * L)) * element_energy<D>(gram, h);
    }
    const auto k = static_cast<Eigen::Index>(ids.size());
    Eigen::Map<Eigen::MatrixXd> A(local.data() + start[static_cast<std::size_t>(e)], k, k);
    Eigen::Map<Eigen::MatrixXd> r(local.data() + start[static_cast<std::size_t>(e)] + static_cast<std::size_t>(k * k), k, m);
    A.noalias() = C * G * C.transpose();
    r.noalias() = C * g;
  });

  const int n = lr.num_basis();
  std::vector<Eigen::Triplet<double, int>> trip;
  std::size_t nnz = 0;
  for (int e = 0; e < ne; ++e) nnz += lr.element_support(e).size() * lr.element_support(e).size();
  trip.reserve(nnz);
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, m);
  for (int e = 0; e < ne; ++e) {
    const std::span<const int> ids = lr.element_support(e);
    const auto k = static_cast<Eigen::Index>(ids.size());
    const double* A = local.data() + start[static_cast<std::size_t>(e)];
    for (Eigen::Index c = 0; c < k; ++c)
      for (Eigen::Index r = 0; r < k; ++r) trip.emplace_back(ids[static_cast<std::size_t>(r)], ids[static_cast<std::size_t>(c)], A[c * k + r]);
    for (int c = 0; c < m; ++c)
      for (Eigen::Index r = 0; r < k; ++r) rhs(ids[static_cast<std::size_t>(r)], c) += A[k * k + c * k + r];
  }
  SparseMatrix M(n, n);
  M.setFromTriplets(trip.begin(), trip.end());
  std::vector<Eigen::Triplet<double, int>>().swap(trip);
  const std::unique_ptr<LinearSolver> solver = make_solver("cholmod");
  try {
    solver->compute(M);
  } catch (const Error&) {
    throw Error("fit: the least-squares system is singular (" + std::to_string(data.size()) + " points for " +
                std::to_string(n) + " coefficients; give more points or a positive smoothing weight)");
  }
  LeastSquaresResult res;
  res.coefs.assign(static_cast<std::size_t>(n) * static_cast<std::size_t>(m), 0.0);
  for (int c = 0; c < m; ++c) {
    const Eigen::VectorXd x = solver->solve(rhs.col(c));
    for (int i = 0; i < n; ++i) res.coefs[static_cast<std::size_t>(i) * static_cast<std::size_t>(m) + static_cast<std::size_t>(c)] = x[i];
  }

  // Errors: per element its Bezier net C^T c, then one Bernstein evaluation per point.
  res.errors.assign(data.size(), 0.0);
  parallel_for(ne, threads, [&](std::ptrdiff_t ei) {
    const int e = static_cast<int>(ei);
    const int first = where.offsets[static_cast<std::size_t>(e)], last = where.offsets[static_cast<std::size_t>(e) + 1];
    if (first == last) return;
    const Box<D>& box = lr.element(e);
    const std::span<const int> ids = lr.element_support(e);
    const Eigen::MatrixXd C = extraction_operator(deg, lr.basis_functions(), ids, box);
    Eigen::MatrixXd c(static_cast<Eigen::Index>(ids.size()), m);
    for (std::size_t r = 0; r < ids.size(); ++r)
      for (int j = 0; j < m; ++j) c(static_cast<Eigen::Index>(r), j) = res.coefs[static_cast<std::size_t>(ids[r]) * static_cast<std::size_t>(m) + static_cast<std::size_t>(j)];
    const Eigen::MatrixXd net = C.transpose() * c;  // nb x m
    with_degree<D>(deg, [&](auto P) {
      element_errors<D, P()>(deg, box, data, points_of(where, e), net.data(), nb, res.errors);
    });
  });
  return res;
}

template <int D>
LRSpline<D> with_coefficients(const LRSpline<D>& lr, int dim, std::span<const double> coefs) {
  require(dim >= 1 && coefs.size() == static_cast<std::size_t>(lr.num_basis()) * static_cast<std::size_t>(dim),
          "fit: " + std::to_string(coefs.size()) + " coefficients for " + std::to_string(lr.num_basis()) +
              " B-splines of " + std::to_string(dim) + " values");
  std::vector<LRBSpline<D>> basis(lr.basis_functions().begin(), lr.basis_functions().end());
  for (std::size_t i = 0; i < basis.size(); ++i)
    basis[i].coef.assign(coefs.begin() + static_cast<std::ptrdiff_t>(i) * dim,
                         coefs.begin() + static_cast<std::ptrdiff_t>(i + 1) * dim);
  // The ids depend on the knots only, so coefficient i stays with B-spline i through the constructor's sort.
  return LRSpline<D>(lr.degrees(), dim, false, std::move(basis), lr.mesh());
}

template PointsByElement locate_points(const LRSpline<2>&, std::span<const Param<2>>, int);
template PointsByElement locate_points(const LRSpline<3>&, std::span<const Param<3>>, int);
template LeastSquaresResult least_squares_fit(const LRSpline<2>&, const ScatteredData<2>&, const PointsByElement&, double, int);
template LeastSquaresResult least_squares_fit(const LRSpline<3>&, const ScatteredData<3>&, const PointsByElement&, double, int);
template LRSpline<2> with_coefficients(const LRSpline<2>&, int, std::span<const double>);
template LRSpline<3> with_coefficients(const LRSpline<3>&, int, std::span<const double>);

}  // namespace trivar
