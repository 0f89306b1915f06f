#pragma once
// Adaptive refinement: solve on the LR space, estimate (residual_indicators), mark (Dorfler, fraction beta),
// refine the LR mesh (refine_dorfler), repeat; one ConvergenceRow per solve.
#include <functional>
#include <string>
#include <vector>

#include "trivar/iga/convergence_table.hpp"
#include "trivar/iga/error_norms.hpp"
#include "trivar/iga/poisson.hpp"
#include "trivar/lr/refinement.hpp"

namespace trivar {

struct AdaptiveOptions {
  int steps = 5;       // solves (the last one is not refined after)
  double beta = 0.3;   // Dorfler fraction in (0, 1]
  RefineOptions refine;
  std::string solver = "cholmod";
};

// geometry: the initial LR space (refined in place: on return it is the space of the last solve, whose
// coefficients go to *coefs when given). exact may be null (errors then reported as -1). Calls report(row)
// after each solve when given. Throws trivar::Error for steps < 1 or beta outside (0, 1].
template <int D>
std::vector<ConvergenceRow> adaptive_poisson(LRSpline<D>& geometry, const PoissonProblem<D>& problem,
                                             const ExactSolution<D>& exact, const AdaptiveOptions& options,
                                             const std::function<void(const ConvergenceRow&)>& report = {},
                                             Eigen::VectorXd* coefs = nullptr, int threads = 0);

}  // namespace trivar
