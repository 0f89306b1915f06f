#include "trivar/iga/refined_poisson.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "trivar/core/parallel.hpp"
#include "trivar/iga/refined_assembly.hpp"
#include "trivar/iga/refined_boundary.hpp"

namespace trivar {

template <int D>
RefinedSystem poisson_system(const RefinedSpace<D>& g, const PoissonProblem<D>& problem, int threads,
                             const ElementPartition& part) {
  return assemble_refined_system<D>(
      g, 1, threads,
      [&](const RefinedPoint<D>& p, const std::vector<double>& grad, double dV, Eigen::MatrixXd& K, Eigen::VectorXd& b) {
        const Eigen::Index m = static_cast<Eigen::Index>(p.R.size());
        const double k = problem.conductivity ? problem.conductivity(p.x.data()) : 1.0;
        const double f = problem.source ? problem.source(p.x.data()) : 0.0;
        const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, D, Eigen::RowMajor>> G(grad.data(), m, D);
        K.noalias() += (k * dV) * G * G.transpose();
        b += (f * dV) * Eigen::Map<const Eigen::VectorXd>(p.R.data(), m);
      },
      [&](const RefinedElement<D>& el, Eigen::VectorXd& b) {
        if (!problem.flux) return;
        const auto flux = [&](const double* x, const double* n, double* t) { t[0] = problem.flux(x, n); };
        add_side_loads<D>(g, el, problem.neumann, 1, flux, b);
        add_trimmed_side_loads<D>(g, el, 1, flux, b);
      },
      part);
}

template <int D>
FixedDofs refined_fixed_dofs(const RefinedSpace<D>& g, int components, const std::vector<DirichletCondition<D>>& conditions) {
  FixedDofs fixed = project_dirichlet(g, components, conditions);
  fix_inactive(g, components, fixed);
  return fixed;
}

template <int D>
SolveResult solve_poisson(const RefinedSpace<D>& g, const PoissonProblem<D>& problem, LinearSolver& solver, int threads) {
  const auto t0 = std::chrono::steady_clock::now();
  auto [A, rhs] = poisson_system(g, problem, threads, {});
  return solve_constrained(A, rhs, refined_fixed_dofs(g, 1, problem.dirichlet), solver, t0);
}

template <int D>
void error_norms_per_element(const RefinedSpace<D>& g, const Eigen::VectorXd& coefs, int components, const ExactSolution<D>& exact,
                             std::vector<double>& l2, std::vector<double>& h1, int threads, const ElementPartition& part) {
  const int E = g.num_elements(), N = g.num_basis;
  l2.assign(static_cast<std::size_t>(E), 0.0);
  h1.assign(static_cast<std::size_t>(E), 0.0);
  const std::pair<int, int> range = part.layers(E);
  parallel_for(range.second - range.first, threads, [&](std::ptrdiff_t i) {
    const std::ptrdiff_t e = range.first + i;
    const RefinedElement<D>& el = g.elements[static_cast<std::size_t>(e)];
    const std::size_t nc = static_cast<std::size_t>(components);
    RefinedPoint<D> p;
    std::vector<double> grad, uh(nc), ue(nc), guh(nc * D), ge(nc * D);
    double sl2 = 0, sh1 = 0;
    for_each_element_point<D>(el, g.degrees[0] + 2, [&](const Param<D>& u, double w) {
      refined_point(g, el, u, p);
      const double dV = physical_gradients(p, grad) * w;
      std::fill(uh.begin(), uh.end(), 0.0);
      std::fill(guh.begin(), guh.end(), 0.0);
      for (std::size_t c = 0; c < nc; ++c)
        for (std::size_t l = 0; l < el.ids.size(); ++l) {
          const double a = coefs[static_cast<Eigen::Index>(c) * N + el.ids[l]];
          uh[c] += a * p.R[l];
          for (std::size_t k = 0; k < D; ++k) guh[c * D + k] += a * grad[l * D + k];
        }
      exact(p.x.data(), ue.data(), ge.data());
      for (std::size_t c = 0; c < nc; ++c) sl2 += (uh[c] - ue[c]) * (uh[c] - ue[c]) * dV;
      for (std::size_t k = 0; k < nc * D; ++k) sh1 += (guh[k] - ge[k]) * (guh[k] - ge[k]) * dV;
    });
    l2[static_cast<std::size_t>(e)] = sl2;
    h1[static_cast<std::size_t>(e)] = sh1;
  });
}

template <int D>
ErrorNorms error_norms(const RefinedSpace<D>& g, const Eigen::VectorXd& coefs, int components, const ExactSolution<D>& exact, int threads,
                       const ElementPartition& part) {
  std::vector<double> l2, h1;
  error_norms_per_element(g, coefs, components, exact, l2, h1, threads, part);
  ErrorNorms e;
  for (std::size_t i = 0; i < l2.size(); ++i) {
    e.l2 += l2[i];
    e.h1 += h1[i];
  }
  return {std::sqrt(e.l2), std::sqrt(e.h1)};
}

#define TRIVAR_INSTANTIATE(D)                                                                                         \
  template RefinedSystem poisson_system(const RefinedSpace<D>&, const PoissonProblem<D>&, int, const ElementPartition&); \
  template FixedDofs refined_fixed_dofs(const RefinedSpace<D>&, int, const std::vector<DirichletCondition<D>>&);     \
  template SolveResult solve_poisson(const RefinedSpace<D>&, \
                                     const PoissonProblem<D>&, LinearSolver&, int);                                   \
  template void error_norms_per_element(const RefinedSpace<D>&, \
                                        const Eigen::VectorXd&, int, const ExactSolution<D>&, std::vector<double>&,  \
                                        std::vector<double>&, int, const ElementPartition&);                         \
  template ErrorNorms error_norms(const RefinedSpace<D>&, const Eigen::VectorXd&,   \
                                  int, const ExactSolution<D>&, int, const ElementPartition&);
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

}  // namespace trivar
