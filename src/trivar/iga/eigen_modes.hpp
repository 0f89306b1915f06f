#pragma once
// Generalised symmetric eigenproblems K x = lambda M x (free vibration, Laplace eigenvalues): the lowest
// modes by Spectra's Lanczos iteration in shift-invert mode, (K - sigma M)^{-1} M, with the shifted matrix
// factorised once by CHOLMOD.
#include <chrono>
#include <vector>

#include <Eigen/Core>

#include "trivar/iga/assembler.hpp"
#include "trivar/iga/dirichlet.hpp"
#include "trivar/iga/elasticity.hpp"
#include "trivar/iga/multipatch_space.hpp"
#include "trivar/iga/sparse_matrix.hpp"
#include "trivar/iga/tensor_space.hpp"

namespace trivar {

struct ModesResult {
  Eigen::VectorXd values;   // ascending
  Eigen::MatrixXd vectors;  // one column per mode, every dof (fixed ones zero), M-normalised
  int dofs = 0;             // free dofs
  double assembly_seconds = 0, solve_seconds = 0;
};

// The `count` smallest eigenpairs on the free dofs (K positive definite there, M positive definite).
// sigma: shift below the smallest wanted eigenvalue. Throws trivar::Error for count outside
// 1 .. free dofs - 1 or when the iteration does not converge.
ModesResult lowest_modes(const SparseMatrix& K, const SparseMatrix& M, const FixedDofs& fixed, int count,
                         double sigma = 0.0);

// lowest_modes, timed: assembly_seconds from assembly_start to the call, solve_seconds the eigensolve.
ModesResult timed_lowest_modes(std::chrono::steady_clock::time_point assembly_start, const SparseMatrix& K,
                               const SparseMatrix& M, const FixedDofs& fixed, int count, double sigma);

// The mass form integral of u v of a scalar unknown.
template <int D>
BilinearForm<D> scalar_mass_form();

// The shift of elastic_modes from the traces of K and M: below zero, so K - sigma M stays positive definite
// when too few conditions leave rigid-body modes (lambda = 0).
double rigid_body_shift(double stiffness_trace, double mass_trace);

// Eigenpairs of -Laplace u = lambda u with u = 0 on the given faces (natural condition elsewhere).
template <int D>
ModesResult laplace_modes(const MultipatchSpace<D>& space, const std::vector<Face>& dirichlet, int count,
                          int threads = 0);
template <int D>
ModesResult laplace_modes(const TensorSpace<D>& space, const std::vector<Face>& dirichlet, int count, int threads = 0);

// Free vibration: K x = omega^2 M x with the elastic stiffness and the density-weighted mass of the problem's
// materials, under its displacement conditions (values ignored: they fix components to zero); tractions and
// body forces play no part. Eigenvalues are omega^2 (angular frequency squared). Without enough conditions
// the rigid-body modes come first, with eigenvalues ~0.
template <int D>
ModesResult elastic_modes(const MultipatchSpace<D>& space, const ElasticityProblem<D>& problem, int count,
                          int threads = 0);

}  // namespace trivar
