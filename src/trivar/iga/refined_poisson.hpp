#pragma once
// The Poisson problem (poisson.hpp) on a locally refined space (LR, HB, THB; refined_space.hpp): element loop
// with the element extraction operators, dense element matrices, Neumann loads on the element sides along the
// Neumann faces, strong Dirichlet conditions by L2 projection onto the functions non-zero on the Dirichlet sides
// (both in refined_boundary.hpp), L2 / H1 errors per element of scalar and vector fields.
#include <vector>

#include <Eigen/Core>

#include "trivar/iga/error_norms.hpp"
#include "trivar/iga/refined_assembly.hpp"
#include "trivar/iga/refined_space.hpp"
#include "trivar/iga/poisson.hpp"

namespace trivar {

// Same conventions as the tensor-patch solve_poisson: boundary faces neither Dirichlet nor Neumann are
// natural (g = 0); a face listed as both is Dirichlet. On a trimmed space the trimming boundary is a Neumann
// boundary (the flux applies there too), and functions without support in the trimmed domain are fixed at 0.
template <int D>
SolveResult solve_poisson(const RefinedSpace<D>& geometry, const PoissonProblem<D>& problem, LinearSolver& solver, int threads = 0);

// The matrix and load of solve_poisson over a part of the elements, before the Dirichlet conditions.
template <int D>
RefinedSystem poisson_system(const RefinedSpace<D>& geometry, const PoissonProblem<D>& problem, int threads,
                             const ElementPartition& part);
// The Dirichlet dofs of the problems on a refined space: the projected conditions, and on a trimmed space the
// functions without support inside fixed at 0.
template <int D>
FixedDofs refined_fixed_dofs(const RefinedSpace<D>& geometry, int components, const std::vector<DirichletCondition<D>>& conditions);

// Squared L2 and H1-seminorm errors per element (sums give the squares of the global errors) of a field with
// `components` components (coefs component-major, exact as in error_norms.hpp).
template <int D>
void error_norms_per_element(const RefinedSpace<D>& geometry, const Eigen::VectorXd& coefs, int components, const ExactSolution<D>& exact,
                             std::vector<double>& l2, std::vector<double>& h1, int threads = 0,
                             const ElementPartition& part = {});
// The global errors (per-element squares summed in element order); with a part, over its elements only.
template <int D>
ErrorNorms error_norms(const RefinedSpace<D>& geometry, const Eigen::VectorXd& coefs, int components, const ExactSolution<D>& exact, int threads = 0,
                       const ElementPartition& part = {});

}  // namespace trivar
