#include "trivar/iga/adaptive_loop.hpp"

#include <cmath>
#include <optional>

#include "trivar/core/error.hpp"
#include "trivar/iga/error_indicator.hpp"
#include "trivar/iga/refined_poisson.hpp"
#include "trivar/iga/refined_space.hpp"
#include "trivar/lr/dorfler.hpp"

namespace trivar {

namespace {

template <int D>
void refine_marked(LRSpline<D>& g, std::span<const double> eta, const AdaptiveOptions& o) {
  refine_dorfler(g, eta, o.beta, o.refine);
}

template <int D>
void refine_marked(HierarchicalSpline<D>& g, std::span<const double> eta, const AdaptiveOptions& o) {
  const std::vector<int> marked = dorfler_mark(eta, o.beta);
  if (o.admissible) g.refine_elements_admissible(marked, o.admissible);
  else g.refine_elements(marked);
}

// The loop of an LR or a hierarchical geometry: its space rebuilt after every refinement.
template <class Geometry, int D>
std::vector<ConvergenceRow> adaptive(Geometry& g, const PoissonProblem<D>& problem, const ExactSolution<D>& exact,
                                     const AdaptiveOptions& o, const std::function<void(const ConvergenceRow&)>& report,
                                     Eigen::VectorXd* coefs, int threads, const RefinedPoissonSolve<D>& solve) {
  std::optional<RefinedSpace<D>> space;
  AdaptiveModel<D> model;
  model.space = [&]() -> const RefinedSpace<D>& {
    if (!space) space = refined_space(g, threads);
    return *space;
  };
  model.refine = [&](std::span<const double> eta) {
    refine_marked(g, eta, o);
    space.reset();
  };
  return adaptive_poisson<D>(model, problem, exact, o, report, coefs, threads, solve);
}

}  // namespace


template <int D>
std::vector<ConvergenceRow> adaptive_poisson(LRSpline<D>& g, const PoissonProblem<D>& problem, const ExactSolution<D>& exact,
                                             const AdaptiveOptions& o,
                                             const std::function<void(const ConvergenceRow&)>& report,
                                             Eigen::VectorXd* coefs, int threads,
                                             const RefinedPoissonSolve<D>& solve) {
  return adaptive<LRSpline<D>, D>(g, problem, exact, o, report, coefs, threads, solve);
}

template <int D>
std::vector<ConvergenceRow> adaptive_poisson(HierarchicalSpline<D>& g, const PoissonProblem<D>& problem,
                                             const ExactSolution<D>& exact, const AdaptiveOptions& o,
                                             const std::function<void(const ConvergenceRow&)>& report,
                                             Eigen::VectorXd* coefs, int threads,
                                             const RefinedPoissonSolve<D>& solve) {
  return adaptive<HierarchicalSpline<D>, D>(g, problem, exact, o, report, coefs, threads, solve);
}

template <int D>
std::vector<ConvergenceRow> adaptive_poisson(const AdaptiveModel<D>& model, const PoissonProblem<D>& problem,
                                             const ExactSolution<D>& exact, const AdaptiveOptions& o,
                                             const std::function<void(const ConvergenceRow&)>& report,
                                             Eigen::VectorXd* coefs, int threads, const RefinedPoissonSolve<D>& solve) {
  require(o.steps >= 1, "adaptive: --steps must be at least 1, got " + std::to_string(o.steps));
  require(o.beta > 0 && o.beta <= 1, "adaptive: --beta must lie in (0, 1], got " + std::to_string(o.beta));
  std::vector<ConvergenceRow> rows;
  for (int step = 0; step < o.steps; ++step) {
    const RefinedSpace<D>& space = model.space();
    const SolveResult r = solve ? solve(space, problem) : solve_poisson(space, problem, *make_solver(o.solver), threads);
    ConvergenceRow row;
    row.step = step;
    row.elements = space.num_elements();
    row.dofs = r.dofs;
    row.assembly_seconds = r.assembly_seconds;
    row.solve_seconds = r.solve_seconds;
    row.l2 = row.h1 = -1;
    if (exact) {
      std::vector<double> l2, h1;
      error_norms_per_element(space, r.coefs, 1, exact, l2, h1, threads);
      row.l2 = row.h1 = 0;
      for (std::size_t e = 0; e < l2.size(); ++e) {
        row.l2 += l2[e];
        row.h1 += h1[e];
      }
      row.l2 = std::sqrt(row.l2);
      row.h1 = std::sqrt(row.h1);
    }
    const std::vector<double> eta = residual_indicators(space, problem, r.coefs, threads, model.across);
    row.estimate = 0;
    for (double x : eta) row.estimate += x * x;
    row.estimate = std::sqrt(row.estimate);
    rows.push_back(row);
    if (report) report(row);
    if (step + 1 == o.steps) {
      if (coefs) *coefs = r.coefs;
      break;
    }
    model.refine(eta);
  }
  return rows;
}

#define TRIVAR_INSTANTIATE(G, D)                                                                                  \
  template std::vector<ConvergenceRow> adaptive_poisson(G<D>&, const PoissonProblem<D>&, const ExactSolution<D>&, \
                                                        const AdaptiveOptions&,                                   \
                                                        const std::function<void(const ConvergenceRow&)>&,        \
                                                        Eigen::VectorXd*, int, const RefinedPoissonSolve<D>&);
TRIVAR_INSTANTIATE(LRSpline, 2)
TRIVAR_INSTANTIATE(LRSpline, 3)
TRIVAR_INSTANTIATE(HierarchicalSpline, 2)
TRIVAR_INSTANTIATE(HierarchicalSpline, 3)
#undef TRIVAR_INSTANTIATE
template std::vector<ConvergenceRow> adaptive_poisson(const AdaptiveModel<2>&, const PoissonProblem<2>&, const ExactSolution<2>&,
                                                      const AdaptiveOptions&, const std::function<void(const ConvergenceRow&)>&,
                                                      Eigen::VectorXd*, int, const RefinedPoissonSolve<2>&);
template std::vector<ConvergenceRow> adaptive_poisson(const AdaptiveModel<3>&, const PoissonProblem<3>&, const ExactSolution<3>&,
                                                      const AdaptiveOptions&, const std::function<void(const ConvergenceRow&)>&,
                                                      Eigen::VectorXd*, int, const RefinedPoissonSolve<3>&);

}  // namespace trivar
