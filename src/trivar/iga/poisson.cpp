#include "trivar/iga/poisson.hpp"

#include <chrono>

#include "trivar/core/error.hpp"
#include "trivar/iga/boundary_integral.hpp"
#include "trivar/iga/multipatch_assembly.hpp"

namespace trivar {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

SolveResult solve_constrained(SparseMatrix& A, Eigen::VectorXd& b, const FixedDofs& fixed, LinearSolver& solver,
                              std::chrono::steady_clock::time_point assembly_start) {
  apply_dirichlet(A, b, fixed);
  SolveResult r;
  r.assembly_seconds = seconds_since(assembly_start);
  const auto t1 = std::chrono::steady_clock::now();
  solver.compute(A);
  r.coefs = solver.solve(b);
  r.solve_seconds = seconds_since(t1);
  r.stats = solver.stats();
  r.dofs = fixed.num_free();
  return r;
}

template <int D>
void add_face_load(const MultipatchSpace<D>& space, const std::vector<Face>& faces, int components,
                   const std::function<void(const double* x, const double* normal, double* g)>& g, Eigen::VectorXd& b) {
  const int N = space.num_basis;
  std::vector<double> v(static_cast<std::size_t>(components));
  for (const Face& f : faces) {
    require(f.patch >= 0 && f.patch < space.num_patches(), "iga: no patch " + std::to_string(f.patch));
    const TensorSpace<D>& patch = space.patches[static_cast<std::size_t>(f.patch)];
    const std::vector<int>& ids = space.global[static_cast<std::size_t>(f.patch)];
    integrate_face<D>(patch, f, patch.geometry.degree(0) + 2, [&](const FacePoint<D>& p) {
      g(p.x.data(), p.normal.data(), v.data());
      for (std::size_t i = 0; i < p.ids.size(); ++i)
        for (int c = 0; c < components; ++c)
          b[static_cast<Eigen::Index>(c) * N + ids[static_cast<std::size_t>(p.ids[i])]] +=
              p.weight * p.values[i] * v[static_cast<std::size_t>(c)];
    });
  }
}

template <int D>
SolveResult solve_loaded(const MultipatchSpace<D>& space, SparseMatrix& A, int components,
                         const std::function<void(const double* x, double* f)>& f, const std::vector<Face>& faces,
                         const std::function<void(const double* x, const double* normal, double* g)>& g,
                         const std::vector<DirichletCondition<D>>& conditions, LinearSolver& solver,
                         std::chrono::steady_clock::time_point assembly_start, int threads) {
  Eigen::VectorXd b = f ? assemble_load<D>(space, components, f, threads)
                        : Eigen::VectorXd::Zero(static_cast<Eigen::Index>(space.num_basis) * components);
  if (g && !faces.empty()) add_face_load<D>(space, faces, components, g, b);
  const FixedDofs fixed = project_dirichlet(space, components, conditions);
  return solve_constrained(A, b, fixed, solver, assembly_start);
}

template <int D>
BilinearForm<D> poisson_form(const PoissonProblem<D>& problem) {
  BilinearForm<D> form;
  form.coefficients = [k = problem.conductivity](const double* x, double* P) {
    const double kx = k ? k(x) : 1.0;
    for (int a = 0; a < (D + 1) * (D + 1); ++a) P[a] = 0.0;
    for (int a = 1; a <= D; ++a) P[a * (D + 1) + a] = kx;
  };
  return form;
}

template <int D>
SolveResult solve_poisson(const MultipatchSpace<D>& space, const PoissonProblem<D>& problem, LinearSolver& solver,
                          int threads) {
  const auto t0 = std::chrono::steady_clock::now();
  const BilinearForm<D> form = poisson_form(problem);
  SparseMatrix A = assemble_matrix<D>(space, [&](int) { return form; }, threads);
  std::function<void(const double*, double*)> f;
  if (problem.source) f = [&](const double* x, double* out) { out[0] = problem.source(x); };
  std::function<void(const double*, const double*, double*)> g;
  if (problem.flux) g = [&](const double* x, const double* n, double* out) { out[0] = problem.flux(x, n); };
  return solve_loaded(space, A, 1, f, problem.neumann, g, problem.dirichlet, solver, t0, threads);
}

template <int D>
SolveResult solve_poisson(const TensorSpace<D>& space, const PoissonProblem<D>& problem, LinearSolver& solver,
                          int threads) {
  return solve_poisson(single_patch_space(space), problem, solver, threads);
}

#define TRIVAR_INSTANTIATE(D)                                                                                        \
  template BilinearForm<D> poisson_form(const PoissonProblem<D>&);                                                   \
  template void add_face_load(const MultipatchSpace<D>&, const std::vector<Face>&, int,                              \
                              const std::function<void(const double*, const double*, double*)>&, Eigen::VectorXd&); \
  template SolveResult solve_loaded(const MultipatchSpace<D>&, SparseMatrix&, int,                                   \
                                    const std::function<void(const double*, double*)>&, const std::vector<Face>&,      \
                                    const std::function<void(const double*, const double*, double*)>&,                \
                                    const std::vector<DirichletCondition<D>>&, LinearSolver&,                           \
                                    std::chrono::steady_clock::time_point, int);                                       \
  template SolveResult solve_poisson(const MultipatchSpace<D>&, const PoissonProblem<D>&, LinearSolver&, int);       \
  template SolveResult solve_poisson(const TensorSpace<D>&, const PoissonProblem<D>&, LinearSolver&, int);
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

}  // namespace trivar
