#include "trivar/iga/adaptive_loop.hpp"

#include <cmath>

#include "trivar/core/error.hpp"
#include "trivar/iga/error_indicator.hpp"
#include "trivar/iga/lr_poisson.hpp"
#include "trivar/lr/dorfler.hpp"

namespace trivar {

template <int D>
std::vector<ConvergenceRow> adaptive_poisson(LRSpline<D>& g, const PoissonProblem<D>& problem,
                                             const ExactSolution<D>& exact, const AdaptiveOptions& o,
                                             const std::function<void(const ConvergenceRow&)>& report,
                                             Eigen::VectorXd* coefs, int threads) {
  require(o.steps >= 1, "adaptive: --steps must be at least 1, got " + std::to_string(o.steps));
  require(o.beta > 0 && o.beta <= 1, "adaptive: --beta must lie in (0, 1], got " + std::to_string(o.beta));
  std::vector<ConvergenceRow> rows;
  for (int step = 0; step < o.steps; ++step) {
    const auto elements = lr_element_bases(g, threads);
    auto solver = make_solver(o.solver);
    const SolveResult r = solve_poisson(g, elements, problem, *solver, threads);
    ConvergenceRow row;
    row.step = step;
    row.elements = g.num_elements();
    row.dofs = r.dofs;
    row.assembly_seconds = r.assembly_seconds;
    row.solve_seconds = r.solve_seconds;
    row.l2 = row.h1 = -1;
    if (exact) {
      std::vector<double> l2, h1;
      error_norms_per_element(g, elements, r.coefs, 1, exact, l2, h1, threads);
      row.l2 = row.h1 = 0;
      for (std::size_t e = 0; e < l2.size(); ++e) {
        row.l2 += l2[e];
        row.h1 += h1[e];
      }
      row.l2 = std::sqrt(row.l2);
      row.h1 = std::sqrt(row.h1);
    }
    const std::vector<double> eta = residual_indicators(g, elements, problem, r.coefs, threads);
    row.estimate = 0;
    for (double x : eta) row.estimate += x * x;
    row.estimate = std::sqrt(row.estimate);
    rows.push_back(row);
    if (report) report(row);
    if (step + 1 == o.steps) {
      if (coefs) *coefs = r.coefs;
      break;
    }
    refine_dorfler(g, eta, o.beta, o.refine);
  }
  return rows;
}

template std::vector<ConvergenceRow> adaptive_poisson(LRSpline<2>&, const PoissonProblem<2>&, const ExactSolution<2>&,
                                                      const AdaptiveOptions&,
                                                      const std::function<void(const ConvergenceRow&)>&,
                                                      Eigen::VectorXd*, int);
template std::vector<ConvergenceRow> adaptive_poisson(LRSpline<3>&, const PoissonProblem<3>&, const ExactSolution<3>&,
                                                      const AdaptiveOptions&,
                                                      const std::function<void(const ConvergenceRow&)>&,
                                                      Eigen::VectorXd*, int);

}  // namespace trivar
