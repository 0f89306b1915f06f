#include "trivar/iga/error_indicator.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "trivar/core/error.hpp"
#include "trivar/core/parallel.hpp"
#include "trivar/iga/refined_quadrature.hpp"

namespace trivar {

namespace {

// Physical gradient and Laplacian of u_h = sum c_l R_l at an evaluated point. With g = grad_x u:
// d2u/du_a du_b = J^T (Hess_x u) J + sum_c g_c d2x_c/du_a du_b, so Hess_x u = J^{-T} (H_u - sum_c g_c H_c) J^{-1}.
template <int D>
void gradient_and_laplacian(const RefinedPoint<D>& p, const std::vector<int>& ids, const Eigen::VectorXd& coefs,
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
std::vector<double> residual_indicators(const RefinedSpace<D>& g, const PoissonProblem<D>& problem, const Eigen::VectorXd& coefs, int threads,
                                        const ElementAcross<D>& across) {
  require(!problem.conductivity, "iga: the residual indicator supports conductivity k = 1 only");
  const bool multi = !g.blocks.empty();
  require(!multi || across, "iga: the residual indicator on a multi-block space needs the elements across its interfaces");
  const int E = g.num_elements();
  // The element just across a side: the given map, or the locator of the one parameter domain.
  const ElementAcross<D> neighbour = across ? across : [&g](int, int k, int side, const Param<D>& u, Param<D>& v) {
    v = u;
    Param<D> inside = u;
    inside[k] += (side == 0 ? -1.0 : 1.0) * 1e-9 * g.domain.extent(k);
    return g.locate(inside);
  };
  std::vector<double> eta(static_cast<std::size_t>(E));
  auto is_dirichlet = [&](const Face& f) {
    for (const auto& cond : problem.dirichlet)
      if (std::find(cond.faces.begin(), cond.faces.end(), f) != cond.faces.end()) return true;
    return false;
  };
  parallel_for(E, threads, [&](std::ptrdiff_t e) {
    const RefinedElement<D>& el = g.elements[static_cast<std::size_t>(e)];
    const Box<D>& dom = multi ? g.blocks[static_cast<std::size_t>(el.block)].domain : g.domain;
    const int nq = g.degrees[0] + 1;
    RefinedPoint<D> p, pn;
    Eigen::Matrix<double, D, 1> grad, gn;
    double lap, lapn, volume = 0, interior = 0;
    for_each_gauss_point<D>(el.box, nq, -1, 0, [&](const Param<D>& u, double w) {
      refined_point(g, el, u, p);
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
    double jumps = 0, neumann = 0;
    for (int k = 0; k < D; ++k)
      for (int side = 0; side < 2; ++side) {
        const Face face{k, side, el.block};
        if (!on_domain_face(dom, el.box, face) || ((el.interface_sides >> (2 * k + side)) & 1u)) {
          for_each_side_point<D>(g, el, k, side, nq,
                                 [&](const Param<D>& u, const RefinedPoint<D>& q, double w, const std::array<double, D>& n) {
            Param<D> v;
            const RefinedElement<D>& nb = g.elements[static_cast<std::size_t>(neighbour(static_cast<int>(e), k, side, u, v))];
            refined_point(g, nb, v, pn);
            gradient_and_laplacian<D>(q, el.ids, coefs, grad, lap);
            gradient_and_laplacian<D>(pn, nb.ids, coefs, gn, lapn);
            double jump = 0;
            for (int c = 0; c < D; ++c) jump += (grad[c] - gn[c]) * n[c];
            jumps += jump * jump * w;
          });
          continue;
        }
        if (is_dirichlet(face)) continue;  // exact boundary values: no residual
        // Neumann side, given or natural (g = 0): the solve imposes k du/dn = g only weakly, so the flux
        // mismatch is a residual like an interior jump, owned by this element alone.
        const bool given = problem.flux && std::find(problem.neumann.begin(), problem.neumann.end(), face) !=
                                               problem.neumann.end();
        for_each_side_point<D>(g, el, k, side, nq,
                               [&](const Param<D>&, const RefinedPoint<D>& q, double w, const std::array<double, D>& n) {
          gradient_and_laplacian<D>(q, el.ids, coefs, grad, lap);
          double mismatch = given ? problem.flux(q.x.data(), n.data()) : 0.0;
          for (int c = 0; c < D; ++c) mismatch -= grad[c] * n[c];
          neumann += mismatch * mismatch * w;
        });
      }
    eta[static_cast<std::size_t>(e)] = std::sqrt(h * h * interior + h * (0.5 * jumps + neumann));
  });
  return eta;
}

template std::vector<double> residual_indicators(const RefinedSpace<2>&, const PoissonProblem<2>&, const Eigen::VectorXd&, int,
                                                 const ElementAcross<2>&);
template std::vector<double> residual_indicators(const RefinedSpace<3>&, const PoissonProblem<3>&, const Eigen::VectorXd&, int,
                                                 const ElementAcross<3>&);

}  // namespace trivar
