#pragma once
// The problems of iga/ (Poisson, linear elasticity, Laplace and free-vibration eigenmodes) on a tensor or
// multipatch space, assembled and solved by all ranks of a PetscSession together: each rank assembles its
// share of every patch's elements (ElementPartition: a slab of element layers) into a distributed PETSc
// matrix (petsc_system.hpp), Dirichlet conditions are eliminated in parallel, linear systems are solved by
// PETSc's conjugate gradients and eigenproblems by SLEPc's Krylov-Schur in shift-invert mode.
//
// Every function is collective (all ranks call it with the same arguments) and returns the whole solution on
// every rank (gathered, for output and error norms); times are the slowest rank's.
#include <string>
#include <vector>

#include "trivar/iga/eigen_modes.hpp"
#include "trivar/iga/elasticity.hpp"
#include "trivar/iga/element_partition.hpp"
#include "trivar/iga/error_norms.hpp"
#include "trivar/iga/poisson.hpp"
#include "trivar/iga/refined_modes.hpp"
#include "trivar/iga/refined_space.hpp"

namespace trivar {

struct PetscSolverOptions {
  // gamg (PETSc's smoothed-aggregation algebraic multigrid; rigid-body modes as near null space in
  // elasticity), hypre (BoomerAMG), bjacobi (block Jacobi, one block per rank, incomplete Cholesky ICC(0)
  // inside), jacobi, or mumps (parallel sparse Cholesky, a direct solve).
  std::string preconditioner = "gamg";
  double tolerance = 1e-10;  // relative residual |b - A x| / |b| of conjugate gradients
  int threads = 1;           // threads of each rank's element loop (0: all cores)
};

// Processor time of the last distributed solve's phases (assembly up to the eliminated system; solve or
// eigensolve), the slowest rank's: on a loaded machine the wall times include waiting for the processor.
struct PhaseCpuSeconds {
  double assembly = 0, solve = 0;
};
const PhaseCpuSeconds& last_phase_cpu_seconds();

// This rank's share of the elements.
ElementPartition rank_partition();

// Throws trivar::Error (on every rank) for an unknown preconditioner, without an active PetscSession, or when
// the iteration does not converge.
template <int D>
SolveResult petsc_solve_poisson(const MultipatchSpace<D>& space, const PoissonProblem<D>& problem,
                                const PetscSolverOptions& options);
template <int D>
SolveResult petsc_solve_elasticity(const MultipatchSpace<D>& space, const ElasticityProblem<D>& problem,
                                   const PetscSolverOptions& options);

// On a locally refined space (LR, HB, THB; refined_space.hpp): each rank assembles a contiguous run of the
// space's elements, and the matrix is preallocated from all ranks' patterns (MATPREALLOCATOR). GAMG gets the
// rigid-body modes of elasticity from the control points, as on tensor spaces.
template <int D>
SolveResult petsc_solve_poisson(const RefinedSpace<D>& space, const PoissonProblem<D>& problem,
                                const PetscSolverOptions& options);
template <int D>
SolveResult petsc_solve_elasticity(const RefinedSpace<D>& space, const ElasticityProblem<D>& problem,
                                   const PetscSolverOptions& options);

// As laplace_modes and elastic_modes (eigen_modes.hpp): the shift-invert systems are solved by the options'
// preconditioner (mumps: exactly; otherwise CG to the options' tolerance, which bounds the eigenvalues'
// accuracy).
template <int D>
ModesResult petsc_laplace_modes(const MultipatchSpace<D>& space, const std::vector<Face>& dirichlet, int count,
                                const PetscSolverOptions& options);
template <int D>
ModesResult petsc_elastic_modes(const MultipatchSpace<D>& space, const ElasticityProblem<D>& problem, int count,
                                const PetscSolverOptions& options);

// On a locally refined space (refined_modes.hpp): each rank assembles a contiguous run of the elements.
template <int D>
ModesResult petsc_laplace_modes(const RefinedSpace<D>& space, const std::vector<Face>& dirichlet, int count,
                                const PetscSolverOptions& options);
template <int D>
ModesResult petsc_elastic_modes(const RefinedSpace<D>& space, const ElasticityProblem<D>& problem, int count,
                                const PetscSolverOptions& options);

// error_norms (error_norms.hpp) with each rank integrating its own elements, the squares summed over ranks.
template <int D>
ErrorNorms petsc_error_norms(const MultipatchSpace<D>& space, const Eigen::VectorXd& coefs, int components,
                             const ExactSolution<D>& exact, int threads = 1);
template <int D>
ErrorNorms petsc_error_norms(const RefinedSpace<D>& space, const Eigen::VectorXd& coefs, int components,
                             const ExactSolution<D>& exact, int threads = 1);

}  // namespace trivar
