#include "trivar/iga/error_indicator.hpp"

#include <cmath>

#include <Eigen/Dense>

#include "trivar/core/error.hpp"
#include "trivar/core/parallel.hpp"
#include "trivar/iga/lr_poisson.hpp"

namespace trivar {

namespace {

// Physical gradient and Laplacian of u_h = sum c_l R_l at an evaluated point. With g = grad_x u:
// d2u/du_a du_b = J^T (Hess_x u) J + sum_c g_c d2x_c/du_a du_b, so Hess_x u = J^{-T} (H_u - sum_c g_c H_c) J^{-1}.
template <int D>
void gradient_and_laplacian(const LRPoint<D>& p, const std::vector<int>& ids, const Eigen::VectorXd& coefs,
                            Eigen::Matrix<double, D, 1>& grad, double& lap) {
  Eigen::Matrix<double, D, D> J, Hu;
  Eigen::Matrix<double, D, 1> du = Eigen::Matrix<double, D, 1>::Zero();
  Hu.setZero();
  for (int r = 0; r < D; ++r)
    for (int s = 0; s < D; ++s) J(r, s) = p.J[r][s];
  for (std::size_t l = 0; l < ids.size(); ++l) {
    const double c = coefs[ids[l]];
    for (int a = 0; a < D; ++a) {
      du[a] += c * p.dR[l * D + static_cast<std::size_t>(a)];
      for (int b = 0; b < D; ++b) Hu(a, b) += c * p.d2R[(l * D + static_cast<std::size_t>(a)) * D + static_cast<std::size_t>(b)];
    }
  }
  const Eigen::Matrix<double, D, D> Jinv = J.inverse();
  grad = Jinv.transpose() * du;
  for (int c = 0; c < D; ++c)
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) Hu(a, b) -= grad[c] * p.H[c][a][b];
  lap = (Jinv.transpose() * Hu * Jinv).trace();
}

}  // namespace

template <int D>
std::vector<double> residual_indicators(const LRSpline<D>& g, const std::vector<LRElementBasis<D>>& elements,
                                        const PoissonProblem<D>& problem, const Eigen::VectorXd& coefs, int threads) {
  require(!problem.conductivity, "iga: the residual indicator supports conductivity k = 1 only");
  const int E = g.num_elements();
  const Box<D>& dom = g.domain();
  const ElementEvaluator<D>& locate = g.evaluator();
  std::vector<double> eta(static_cast<std::size_t>(E));
  parallel_for(E, threads, [&](std::ptrdiff_t e) {
    const LRElementBasis<D>& el = elements[static_cast<std::size_t>(e)];
    const int nq = g.degree(0) + 1;
    LRPoint<D> p, pn;
    Eigen::Matrix<double, D, 1> grad, gn;
    double lap, lapn, volume = 0, interior = 0;
    for_each_gauss_point<D>(el.box, nq, -1, 0, [&](const Param<D>& u, double w) {
      lr_point(g, el, u, p);
      gradient_and_laplacian<D>(p, el.ids, coefs, grad, lap);
      Eigen::Matrix<double, D, D> J;
      for (int r = 0; r < D; ++r)
        for (int s = 0; s < D; ++s) J(r, s) = p.J[r][s];
      const double dV = std::abs(J.determinant()) * w;
      const double res = (problem.source ? problem.source(p.x.data()) : 0.0) + lap;
      interior += res * res * dV;
      volume += dV;
    });
    const double h = std::pow(volume, 1.0 / D);
    double jumps = 0;
    for (int k = 0; k < D; ++k)
      for (int side = 0; side < 2; ++side) {
        const double at = side == 0 ? el.box.lo[k] : el.box.hi[k];
        if (at == (side == 0 ? dom.lo[k] : dom.hi[k])) continue;  // boundary side: Dirichlet data, no jump
        for_each_gauss_point<D>(el.box, nq, k, side, [&](const Param<D>& u, double w) {
          // The neighbour is the element just across the side at this point.
          Param<D> across = u;
          across[k] += (side == 0 ? -1.0 : 1.0) * 1e-9 * dom.extent(k);
          const LRElementBasis<D>& nb = elements[static_cast<std::size_t>(locate.find_element(across))];
          lr_point(g, el, u, p);
          lr_point(g, nb, u, pn);
          gradient_and_laplacian<D>(p, el.ids, coefs, grad, lap);
          gradient_and_laplacian<D>(pn, nb.ids, coefs, gn, lapn);
          double sw;
          std::array<double, D> n;
          side_measure<D>(p.J, k, side, sw, n);
          double jump = 0;
          for (int c = 0; c < D; ++c) jump += (grad[c] - gn[c]) * n[c];
          jumps += jump * jump * sw * w;
        });
      }
    eta[static_cast<std::size_t>(e)] = std::sqrt(h * h * interior + 0.5 * h * jumps);
  });
  return eta;
}

template std::vector<double> residual_indicators(const LRSpline<2>&, const std::vector<LRElementBasis<2>>&,
                                                 const PoissonProblem<2>&, const Eigen::VectorXd&, int);
template std::vector<double> residual_indicators(const LRSpline<3>&, const std::vector<LRElementBasis<3>>&,
                                                 const PoissonProblem<3>&, const Eigen::VectorXd&, int);

}  // namespace trivar
