#pragma once
// Adaptive refinement on a locally refined space: solve (refined_poisson), estimate (residual_indicators), mark
// (Dorfler, fraction beta), refine, repeat; one ConvergenceRow per solve. The geometry is an LR spline (the
// marked elements refined by the LR strategy of options.refine) or a hierarchical spline (HB or THB: the marked
// leaf elements are refined dyadically, the geometry kept exactly); the loop is the same code for both.
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "trivar/hier/hierarchical_spline.hpp"
#include "trivar/iga/convergence_table.hpp"
#include "trivar/iga/error_indicator.hpp"
#include "trivar/iga/error_norms.hpp"
#include "trivar/iga/poisson.hpp"
#include "trivar/lr/refinement.hpp"

namespace trivar {

struct AdaptiveOptions {
  int steps = 5;       // solves (the last one is not refined after)
  double beta = 0.3;   // Dorfler fraction in (0, 1]
  RefineOptions refine;  // LR geometries only
  std::string solver = "cholmod";
  // Hierarchical geometries: 0 refines the marked leaves only; m >= 2 keeps the mesh admissible of class m (at
  // most m levels of functions act on any element; HierarchicalSpace::refine_elements_admissible).
  int admissible = 0;
};

// The linear solve of each step. Null: solve_poisson with options.solver on this process. The distributed back
// end passes petsc_solve_poisson (iga_petsc/): every rank then runs the whole loop with the gathered solution,
// so their estimates, markings and refinements are the same.
template <int D>
using RefinedPoissonSolve = std::function<SolveResult(const RefinedSpace<D>&, const PoissonProblem<D>&)>;

// geometry: the initial space (refined in place: on return it is the space of the last solve, whose
// coefficients go to *coefs when given). exact may be null (errors then reported as -1). Calls report(row)
// after each solve when given. Throws trivar::Error for steps < 1 or beta outside (0, 1].
template <int D>
std::vector<ConvergenceRow> adaptive_poisson(LRSpline<D>& geometry, const PoissonProblem<D>& problem,
                                             const ExactSolution<D>& exact, const AdaptiveOptions& options,
                                             const std::function<void(const ConvergenceRow&)>& report = {},
                                             Eigen::VectorXd* coefs = nullptr, int threads = 0,
                                             const RefinedPoissonSolve<D>& solve = {});
template <int D>
std::vector<ConvergenceRow> adaptive_poisson(HierarchicalSpline<D>& geometry, const PoissonProblem<D>& problem,
                                             const ExactSolution<D>& exact, const AdaptiveOptions& options,
                                             const std::function<void(const ConvergenceRow&)>& report = {},
                                             Eigen::VectorXd* coefs = nullptr, int threads = 0,
                                             const RefinedPoissonSolve<D>& solve = {});

// The loop over any locally refined model: `space()` is the current analysis space (valid until the next
// refine), `refine(eta)` refines the model given one indicator per element of that space, and `across` is what
// residual_indicators needs to find the neighbours of multi-block spaces (null on one parameter domain). The LR
// and hierarchical loops above and the multi-block loop (fit/multiblock_adaptive.hpp) are this loop.
template <int D>
struct AdaptiveModel {
  std::function<const RefinedSpace<D>&()> space;
  std::function<void(std::span<const double> eta)> refine;
  ElementAcross<D> across;
};
template <int D>
std::vector<ConvergenceRow> adaptive_poisson(const AdaptiveModel<D>& model, const PoissonProblem<D>& problem,
                                             const ExactSolution<D>& exact, const AdaptiveOptions& options,
                                             const std::function<void(const ConvergenceRow&)>& report = {},
                                             Eigen::VectorXd* coefs = nullptr, int threads = 0,
                                             const RefinedPoissonSolve<D>& solve = {});

}  // namespace trivar
