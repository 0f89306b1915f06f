#pragma once
// Linear solvers for symmetric positive definite systems behind one interface, so that a distributed backend
// (PETSc/MPI) can be added as another LinearSolver without touching the problems: a backend receives the
// assembled compressed-row matrix once (compute) and then right-hand sides (solve).
#include <memory>
#include <string>

#include <Eigen/Core>

#include "trivar/iga/sparse_matrix.hpp"

namespace trivar {

struct SolveStats {
  int iterations = 0;     // 0 for direct solvers
  double residual = 0.0;  // relative residual |b - A x| / |b| reported by iterative solvers
};

class LinearSolver {
public:
  virtual ~LinearSolver() = default;
  virtual std::string name() const = 0;
  // Analyses / factorises A, which must stay alive and unchanged until the last solve. Throws trivar::Error
  // when A is not positive definite (direct) or the preconditioner cannot be built.
  virtual void compute(const SparseMatrix& A) = 0;
  // Throws trivar::Error when an iterative solver does not reach its tolerance.
  virtual Eigen::VectorXd solve(const Eigen::VectorXd& b) = 0;
  const SolveStats& stats() const { return stats_; }

protected:
  SolveStats stats_;
};

// "cg" (conjugate gradients, Jacobi preconditioner: no set-up, memory of a few vectors, multithreaded
// products), "cg-ichol" (incomplete Cholesky preconditioner: fewer iterations, factor memory),
// "cholmod" (SuiteSparse supernodal Cholesky). tolerance: relative residual of the iterative solvers.
// Throws trivar::Error for an unknown name.
std::unique_ptr<LinearSolver> make_solver(const std::string& name, double tolerance = 1e-10);

}  // namespace trivar
