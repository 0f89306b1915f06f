#include "trivar/spline/measure.hpp"

#include <cmath>

#include <Eigen/Dense>

#include "trivar/core/error.hpp"
#include "trivar/core/gauss_legendre.hpp"
#include "trivar/spline/derivative_index.hpp"

namespace trivar {

namespace {

// Sum over the tensor grid of per-element Gauss points of weight * integrand(J), J = dim x D Jacobian.
template <int D, class Integrand>
double integrate(const TensorSpline<D>& s, int n, int threads, Integrand&& f) {
  const QuadratureRule rule = gauss_legendre(n);
  std::array<std::vector<double>, D> nodes, weights;
  for (int k = 0; k < D; ++k) {
    const std::vector<double> bp = s.knots(k).breakpoints();
    for (std::size_t e = 0; e + 1 < bp.size(); ++e)
      for (int q = 0; q < n; ++q) {
        nodes[k].push_back(bp[e] + rule.nodes[q] * (bp[e + 1] - bp[e]));
        weights[k].push_back(rule.weights[q] * (bp[e + 1] - bp[e]));
      }
  }
  std::size_t total = 1;
  for (int k = 0; k < D; ++k) total *= nodes[k].size();
  std::vector<Param<D>> params(total);
  std::vector<double> w(total);
  for (std::size_t i = 0; i < total; ++i) {
    std::size_t r = i;
    w[i] = 1.0;
    for (int k = 0; k < D; ++k) {
      const std::size_t q = r % nodes[k].size();
      r /= nodes[k].size();
      params[i][k] = nodes[k][q];
      w[i] *= weights[k][q];
    }
  }
  const int dim = s.dim();
  const std::size_t per = static_cast<std::size_t>(derivative_count(D, 1)) * dim;
  std::vector<double> d(total * per);
  s.eval_derivs_batch(params, 1, d, threads);
  // Summed in index order so the result does not depend on the thread count.
  double sum = 0.0;
  for (std::size_t i = 0; i < total; ++i) {
    const Eigen::Map<const Eigen::MatrixXd> J(d.data() + i * per + dim, dim, D);
    sum += w[i] * f(J);
  }
  return sum;
}

}  // namespace

template <int D>
double measure(const TensorSpline<D>& s, int n, int threads) {
  require(s.dim() >= D, "measure: control dimension " + std::to_string(s.dim()) + " is below the parametric dimension " +
                            std::to_string(D));
  return integrate(s, n, threads, [](const auto& J) { return std::sqrt(std::max(0.0, (J.transpose() * J).determinant())); });
}

template <int D>
double signed_measure(const TensorSpline<D>& s, int n, int threads) {
  require(s.dim() == D, "signed measure: control dimension " + std::to_string(s.dim()) +
                            " differs from the parametric dimension " + std::to_string(D));
  return integrate(s, n, threads, [](const auto& J) { return J.determinant(); });
}

template double measure(const TensorSpline<1>&, int, int);
template double measure(const TensorSpline<2>&, int, int);
template double measure(const TensorSpline<3>&, int, int);
template double signed_measure(const TensorSpline<1>&, int, int);
template double signed_measure(const TensorSpline<2>&, int, int);
template double signed_measure(const TensorSpline<3>&, int, int);

}  // namespace trivar
