#pragma once
// Poisson problem -div(k grad u) = f on a tensor patch or a multipatch space with strong Dirichlet conditions
// (projected, see dirichlet.hpp) and Neumann conditions k du/dn = g.
#include <chrono>
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "trivar/iga/assembler.hpp"
#include "trivar/iga/dirichlet.hpp"
#include "trivar/iga/multipatch_space.hpp"
#include "trivar/iga/solver.hpp"
#include "trivar/iga/tensor_space.hpp"

namespace trivar {

template <int D>
struct PoissonProblem {
  std::function<double(const double* x)> conductivity;  // k > 0 (null: 1)
  std::function<double(const double* x)> source;       // f (null: 0)
  std::vector<DirichletCondition<D>> dirichlet;
  std::vector<Face> neumann;
  std::function<double(const double* x, const double* normal)> flux;  // g = k du/dn (null: 0)
};

// a(u, v) = integral of k grad u . grad v.
template <int D>
BilinearForm<D> poisson_form(const PoissonProblem<D>& problem);

struct SolveResult {
  Eigen::VectorXd coefs;  // per dof (component-major), boundary values included
  int dofs = 0;           // unknowns solved for (free dofs)
  double assembly_seconds = 0, solve_seconds = 0;
  SolveStats stats;
};

// The common end of every static solve: eliminates the fixed dofs, factorises and solves, and reports the
// assembly time (from `assembly_start` to the elimination) and the solve time separately.
SolveResult solve_constrained(SparseMatrix& A, Eigen::VectorXd& b, const FixedDofs& fixed, LinearSolver& solver,
                              std::chrono::steady_clock::time_point assembly_start);

// Adds integral over the faces of sum_c g_c(x, n) v_c (g writes `components` values) to b (global dofs).
template <int D>
void add_face_load(const MultipatchSpace<D>& space, const std::vector<Face>& faces, int components,
                   const std::function<void(const double* x, const double* normal, double* g)>& g, Eigen::VectorXd& b);

// The static loads and the solve shared by the problems on a multipatch space: b = integral of f . v (f null:
// none) plus the face loads g on `faces` (g null: none), Dirichlet conditions projected, then
// solve_constrained. f and g write `components` values.
template <int D>
SolveResult solve_loaded(const MultipatchSpace<D>& space, SparseMatrix& A, int components,
                         const std::function<void(const double* x, double* f)>& f, const std::vector<Face>& faces,
                         const std::function<void(const double* x, const double* normal, double* g)>& g,
                         const std::vector<DirichletCondition<D>>& conditions, LinearSolver& solver,
                         std::chrono::steady_clock::time_point assembly_start, int threads);

template <int D>
SolveResult solve_poisson(const MultipatchSpace<D>& space, const PoissonProblem<D>& problem, LinearSolver& solver,
                          int threads = 0);
template <int D>
SolveResult solve_poisson(const TensorSpace<D>& space, const PoissonProblem<D>& problem, LinearSolver& solver,
                          int threads = 0);

}  // namespace trivar
