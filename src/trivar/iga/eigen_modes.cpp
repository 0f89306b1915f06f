#include "trivar/iga/eigen_modes.hpp"

#include <algorithm>
#include <chrono>
#include <numeric>

#include <Spectra/SymGEigsShiftSolver.h>

#include "trivar/core/error.hpp"
#include "trivar/iga/elasticity.hpp"
#include "trivar/iga/multipatch_assembly.hpp"
#include "trivar/iga/solver.hpp"

namespace trivar {

namespace {

// y = (K - sigma M)^{-1} x, the operator Spectra's shift-invert mode iterates with.
class ShiftInvert {
public:
  using Scalar = double;
  ShiftInvert(const SparseMatrix& K, const SparseMatrix& M) : K_(K), M_(M) {}
  Eigen::Index rows() const { return K_.rows(); }
  Eigen::Index cols() const { return K_.cols(); }
  void set_shift(double sigma) {
    shifted_ = K_ - sigma * M_;
    solver_ = make_solver("cholmod");
    solver_->compute(shifted_);
  }
  void perform_op(const double* x, double* y) const {
    const Eigen::Map<const Eigen::VectorXd> in(x, K_.rows());
    Eigen::Map<Eigen::VectorXd>(y, K_.rows()) = solver_->solve(in);
  }

private:
  const SparseMatrix& K_;
  const SparseMatrix& M_;
  SparseMatrix shifted_;
  std::unique_ptr<LinearSolver> solver_;
};

// Column storage on purpose: Eigen runs row-major products on all threads, which for the many small products
// of a Lanczos iteration costs more in synchronisation than it saves.
class MassProduct {
public:
  using Scalar = double;
  explicit MassProduct(const SparseMatrix& M) : M_(M) {}
  Eigen::Index rows() const { return M_.rows(); }
  Eigen::Index cols() const { return M_.cols(); }
  void perform_op(const double* x, double* y) const {
    Eigen::Map<Eigen::VectorXd>(y, M_.rows()) = M_ * Eigen::Map<const Eigen::VectorXd>(x, M_.rows());
  }

private:
  Eigen::SparseMatrix<double> M_;
};

}  // namespace

ModesResult lowest_modes(const SparseMatrix& K, const SparseMatrix& M, const FixedDofs& fixed, int count,
                         double sigma) {
  const SparseMatrix Kf = free_block(K, fixed), Mf = free_block(M, fixed);
  const int n = static_cast<int>(Kf.rows());
  require(count >= 1 && count < n, "modes: asked for " + std::to_string(count) + " modes of a problem with " +
                                       std::to_string(n) + " free dofs");
  ShiftInvert op(Kf, Mf);
  MassProduct bop(Mf);
  // Single-vector Lanczos can converge to fewer copies of a multiple eigenvalue than it has (the free ball's
  // 5-fold modes lost one when exactly 14 were asked for), so a margin of extra pairs is computed and dropped.
  const int wanted = std::min(n - 1, count + std::max(6, count / 2));
  const int ncv = std::min(n, std::max(2 * wanted + 1, 20));
  Spectra::SymGEigsShiftSolver<ShiftInvert, MassProduct, Spectra::GEigsMode::ShiftInvert> eigs(op, bop, wanted, ncv,
                                                                                              sigma);
  eigs.init();
  eigs.compute(Spectra::SortRule::LargestMagn, 1000, 1e-12);
  require(eigs.info() == Spectra::CompInfo::Successful, "modes: the Lanczos iteration did not converge");
  const Eigen::VectorXd lambda = eigs.eigenvalues();
  const Eigen::MatrixXd vec = eigs.eigenvectors();
  std::vector<int> order(static_cast<std::size_t>(lambda.size()));
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return lambda[a] < lambda[b]; });
  const std::vector<int> free = fixed.free_dofs();
  ModesResult r;
  r.dofs = n;
  r.values.resize(count);
  r.vectors = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(fixed.fixed.size()), count);
  for (int i = 0; i < count; ++i) {
    const int j = order[static_cast<std::size_t>(i)];
    r.values[i] = lambda[j];
    for (int f = 0; f < n; ++f) r.vectors(free[static_cast<std::size_t>(f)], i) = vec(f, j);
  }
  return r;
}

ModesResult timed_lowest_modes(std::chrono::steady_clock::time_point assembly_start, const SparseMatrix& K,
                               const SparseMatrix& M, const FixedDofs& fixed, int count, double sigma) {
  const auto t1 = std::chrono::steady_clock::now();
  ModesResult r = lowest_modes(K, M, fixed, count, sigma);
  r.assembly_seconds = std::chrono::duration<double>(t1 - assembly_start).count();
  r.solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  return r;
}

template <int D>
ModesResult laplace_modes(const MultipatchSpace<D>& space, const std::vector<Face>& dirichlet, int count,
                          int threads) {
  const auto t0 = std::chrono::steady_clock::now();
  const BilinearForm<D> stiffness = poisson_form(PoissonProblem<D>{}), mass = scalar_mass_form<D>();
  const SparseMatrix K = assemble_matrix<D>(space, [&](int) { return stiffness; }, threads);
  const SparseMatrix M = assemble_matrix<D>(space, [&](int) { return mass; }, threads);
  const FixedDofs fixed = project_dirichlet<D>(space, 1, {{dirichlet, {}, nullptr}});
  return timed_lowest_modes(t0, K, M, fixed, count, 0.0);
}

template <int D>
ModesResult laplace_modes(const TensorSpace<D>& space, const std::vector<Face>& dirichlet, int count, int threads) {
  return laplace_modes(single_patch_space(space), dirichlet, count, threads);
}

template <int D>
ModesResult elastic_modes(const MultipatchSpace<D>& space, const ElasticityProblem<D>& problem, int count,
                          int threads) {
  const auto t0 = std::chrono::steady_clock::now();
  const SparseMatrix K = elastic_stiffness(space, problem, threads);
  const SparseMatrix M = elastic_mass(space, problem, threads);
  const FixedDofs fixed = project_dirichlet(space, D, problem.displacement);
  return timed_lowest_modes(t0, K, M, fixed, count, rigid_body_shift(K.diagonal().sum(), M.diagonal().sum()));
}

// A body held by too few conditions has rigid-body modes (lambda = 0, K singular): a shift below zero keeps
// K - sigma M positive definite. Its size, a millionth of the mean diagonal ratio, is far below the lowest
// elastic eigenvalue of any mesh and large enough for a well-conditioned factorisation.
double rigid_body_shift(double stiffness_trace, double mass_trace) { return -1e-6 * stiffness_trace / mass_trace; }

template <int D>
BilinearForm<D> scalar_mass_form() {
  BilinearForm<D> mass;
  mass.value_terms = true;
  mass.gradient_terms = false;
  mass.coefficients = [](const double*, double* P) {
    for (int a = 0; a < (D + 1) * (D + 1); ++a) P[a] = 0.0;
    P[0] = 1.0;
  };
  return mass;
}

#define TRIVAR_INSTANTIATE(D)                                                                                 \
  template BilinearForm<D> scalar_mass_form<D>();                                                              \
  template ModesResult laplace_modes(const MultipatchSpace<D>&, const std::vector<Face>&, int, int);         \
  template ModesResult laplace_modes(const TensorSpace<D>&, const std::vector<Face>&, int, int);             \
  template ModesResult elastic_modes(const MultipatchSpace<D>&, const ElasticityProblem<D>&, int, int);
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

}  // namespace trivar
