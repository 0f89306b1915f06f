#include "trivar/iga/lr_poisson.hpp"

#include <chrono>
#include <cmath>
#include <map>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>

#include "trivar/core/error.hpp"
#include "trivar/core/parallel.hpp"
#include "trivar/iga/lr_quadrature.hpp"

namespace trivar {

namespace {

// Physical gradients [l * D + c] of the active functions and |det J|.
template <int D>
double physical_gradients(const LRPoint<D>& p, std::vector<double>& grad) {
  Eigen::Matrix<double, D, D> J;
  for (int r = 0; r < D; ++r)
    for (int s = 0; s < D; ++s) J(r, s) = p.J[r][s];
  const Eigen::Matrix<double, D, D> JinvT = J.inverse().transpose();
  const int m = static_cast<int>(p.R.size());
  grad.resize(static_cast<std::size_t>(m) * D);
  for (int l = 0; l < m; ++l) {
    const Eigen::Matrix<double, D, 1> g =
        JinvT * Eigen::Map<const Eigen::Matrix<double, D, 1>>(&p.dR[static_cast<std::size_t>(l * D)]);
    for (int c = 0; c < D; ++c) grad[static_cast<std::size_t>(l * D + c)] = g[c];
  }
  return std::abs(J.determinant());
}

}  // namespace

template <int D>
SolveResult solve_poisson(const LRSpline<D>& g, const std::vector<LRElementBasis<D>>& elements,
                          const PoissonProblem<D>& problem, LinearSolver& solver, int threads) {
  const auto t0 = std::chrono::steady_clock::now();
  const int N = g.num_basis(), E = g.num_elements();
  std::vector<Eigen::MatrixXd> Ke(static_cast<std::size_t>(E));
  std::vector<Eigen::VectorXd> be(static_cast<std::size_t>(E));
  parallel_for(E, threads, [&](std::ptrdiff_t e) {
    const LRElementBasis<D>& el = elements[static_cast<std::size_t>(e)];
    const int m = static_cast<int>(el.ids.size());
    Eigen::MatrixXd& K = Ke[static_cast<std::size_t>(e)];
    Eigen::VectorXd& b = be[static_cast<std::size_t>(e)];
    K = Eigen::MatrixXd::Zero(m, m);
    b = Eigen::VectorXd::Zero(m);
    LRPoint<D> p;
    std::vector<double> grad;
    for_each_gauss_point<D>(el.box, g.degree(0) + 1, -1, 0, [&](const Param<D>& u, double w) {
      lr_point(g, el, u, p);
      const double dV = physical_gradients(p, grad) * w;
      const double k = problem.conductivity ? problem.conductivity(p.x.data()) : 1.0;
      const double f = problem.source ? problem.source(p.x.data()) : 0.0;
      const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, D, Eigen::RowMajor>> G(grad.data(), m, D);
      K.noalias() += (k * dV) * G * G.transpose();
      b += (f * dV) * Eigen::Map<const Eigen::VectorXd>(p.R.data(), m);
    });
    // Neumann load: integral of g v over the element's sides on the Neumann faces (p + 2 points per direction,
    // as add_face_load).
    if (problem.flux)
      for (const Face& f : problem.neumann) {
        if (!on_domain_face(g.domain(), el.box, f)) continue;
        for_each_side_point<D>(g, el, f.dir, f.side, g.degree(0) + 2,
                               [&](const Param<D>&, const LRPoint<D>& q, double w, const std::array<double, D>& n) {
                                 b += (w * problem.flux(q.x.data(), n.data())) *
                                      Eigen::Map<const Eigen::VectorXd>(q.R.data(), m);
                               });
      }
  });
  std::vector<Eigen::Triplet<double>> trip;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(N);
  for (int e = 0; e < E; ++e) {
    const auto& ids = elements[static_cast<std::size_t>(e)].ids;
    for (std::size_t i = 0; i < ids.size(); ++i) {
      rhs[ids[i]] += be[static_cast<std::size_t>(e)][static_cast<Eigen::Index>(i)];
      for (std::size_t j = 0; j < ids.size(); ++j)
        trip.emplace_back(ids[i], ids[j], Ke[static_cast<std::size_t>(e)](static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)));
    }
  }
  SparseMatrix A(N, N);
  A.setFromTriplets(trip.begin(), trip.end());

  // Dirichlet: L2 projection onto the functions clamped at the Dirichlet sides.
  FixedDofs fixed;
  fixed.fixed.assign(static_cast<std::size_t>(N), 0);
  fixed.values = Eigen::VectorXd::Zero(N);
  std::map<int, int> local;
  for (const auto& cond : problem.dirichlet)
    for (const Face& f : cond.faces)
      for (int id : lr_face_basis(g, f.dir, f.side)) local.emplace(id, 0);
  int nb = 0;
  for (auto& [id, l] : local) {
    l = nb++;
    fixed.fixed[static_cast<std::size_t>(id)] = 1;
  }
  std::vector<Eigen::Triplet<double>> mtrip;
  Eigen::VectorXd mrhs = Eigen::VectorXd::Zero(nb);
  bool nonzero = false;
  for (const auto& cond : problem.dirichlet) {
    if (!cond.value) continue;
    nonzero = true;
    for (const Face& f : cond.faces)
      for (const auto& el : elements) {
        if (!on_domain_face(g.domain(), el.box, f)) continue;
        for_each_side_point<D>(g, el, f.dir, f.side, g.degree(0) + 2,
                               [&](const Param<D>&, const LRPoint<D>& p, double w, const std::array<double, D>&) {
          double val = 0;
          cond.value(p.x.data(), &val);
          for (std::size_t i = 0; i < el.ids.size(); ++i) {
            const auto it = local.find(el.ids[i]);
            if (it == local.end() || p.R[i] == 0.0) continue;
            mrhs[it->second] += w * p.R[i] * val;
            for (std::size_t j = 0; j < el.ids.size(); ++j) {
              const auto jt = local.find(el.ids[j]);
              if (jt != local.end() && p.R[j] != 0.0) mtrip.emplace_back(it->second, jt->second, w * p.R[i] * p.R[j]);
            }
          }
        });
      }
  }
  if (nonzero && nb > 0) {
    Eigen::SparseMatrix<double> M(nb, nb);
    M.setFromTriplets(mtrip.begin(), mtrip.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(M);
    require(ldlt.info() == Eigen::Success, "iga: singular boundary mass matrix in the Dirichlet projection");
    const Eigen::VectorXd gd = ldlt.solve(mrhs);
    for (const auto& [id, l] : local) fixed.values[id] = gd[l];
  }
  return solve_constrained(A, rhs, fixed, solver, t0);
}

template <int D>
void error_norms_per_element(const LRSpline<D>& g, const std::vector<LRElementBasis<D>>& elements,
                             const Eigen::VectorXd& coefs, const ExactSolution<D>& exact, std::vector<double>& l2,
                             std::vector<double>& h1, int threads) {
  const int E = g.num_elements();
  l2.assign(static_cast<std::size_t>(E), 0.0);
  h1.assign(static_cast<std::size_t>(E), 0.0);
  parallel_for(E, threads, [&](std::ptrdiff_t e) {
    const LRElementBasis<D>& el = elements[static_cast<std::size_t>(e)];
    LRPoint<D> p;
    std::vector<double> grad;
    double sl2 = 0, sh1 = 0;
    for_each_gauss_point<D>(el.box, g.degree(0) + 2, -1, 0, [&](const Param<D>& u, double w) {
      lr_point(g, el, u, p);
      const double dV = physical_gradients(p, grad) * w;
      double uh = 0, guh[D] = {};
      for (std::size_t l = 0; l < el.ids.size(); ++l) {
        const double c = coefs[el.ids[l]];
        uh += c * p.R[l];
        for (int k = 0; k < D; ++k) guh[k] += c * grad[l * D + static_cast<std::size_t>(k)];
      }
      double ue, ge[D];
      exact(p.x.data(), &ue, ge);
      sl2 += (uh - ue) * (uh - ue) * dV;
      for (int k = 0; k < D; ++k) sh1 += (guh[k] - ge[k]) * (guh[k] - ge[k]) * dV;
    });
    l2[static_cast<std::size_t>(e)] = sl2;
    h1[static_cast<std::size_t>(e)] = sh1;
  });
}

#define TRIVAR_INSTANTIATE(D)                                                                                         \
  template SolveResult solve_poisson(const LRSpline<D>&, const std::vector<LRElementBasis<D>>&,                        \
                                     const PoissonProblem<D>&, LinearSolver&, int);                                   \
  template void error_norms_per_element(const LRSpline<D>&, const std::vector<LRElementBasis<D>>&,                     \
                                        const Eigen::VectorXd&, const ExactSolution<D>&, std::vector<double>&,          \
                                        std::vector<double>&, int);
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

}  // namespace trivar
