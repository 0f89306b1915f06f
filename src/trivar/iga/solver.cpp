#include "trivar/iga/solver.hpp"

#include <Eigen/CholmodSupport>
#include <Eigen/IterativeLinearSolvers>

#include "trivar/core/error.hpp"

namespace trivar {

namespace {

template <class Preconditioner>
class CgSolver final : public LinearSolver {
public:
  CgSolver(std::string name, double tolerance) : name_(std::move(name)) { cg_.setTolerance(tolerance); }
  std::string name() const override { return name_; }
  void compute(const SparseMatrix& A) override {
    cg_.setMaxIterations(std::max<Eigen::Index>(1000, 10 * A.rows()));
    cg_.compute(A);
    require(cg_.info() == Eigen::Success, "solver " + name_ + ": the preconditioner could not be built");
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& b) override {
    Eigen::VectorXd x = cg_.solve(b);
    stats_.iterations = static_cast<int>(cg_.iterations());
    stats_.residual = cg_.error();
    require(cg_.info() == Eigen::Success, [&] {
      return "solver " + name_ + ": no convergence after " + std::to_string(cg_.iterations()) +
             " iterations (relative residual " + std::to_string(cg_.error()) + ")";
    });
    return x;
  }

private:
  std::string name_;
  // Both triangles are stored, so the product runs row by row on all threads.
  Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower | Eigen::Upper, Preconditioner> cg_;
};

class CholmodSolver final : public LinearSolver {
public:
  std::string name() const override { return "cholmod"; }
  void compute(const SparseMatrix& A) override {
    const Eigen::SparseMatrix<double> columns = A;  // CHOLMOD reads compressed columns
    llt_.compute(columns);
    require(llt_.info() == Eigen::Success, "solver cholmod: the matrix is not positive definite");
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& b) override {
    Eigen::VectorXd x = llt_.solve(b);
    require(llt_.info() == Eigen::Success, "solver cholmod: the solve failed");
    return x;
  }

private:
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt_;
};

}  // namespace

std::unique_ptr<LinearSolver> make_solver(const std::string& name, double tolerance) {
  if (name == "cg") return std::make_unique<CgSolver<Eigen::DiagonalPreconditioner<double>>>(name, tolerance);
  if (name == "cg-ichol")
    return std::make_unique<CgSolver<Eigen::IncompleteCholesky<double, Eigen::Lower, Eigen::AMDOrdering<int>>>>(
        name, tolerance);
  if (name == "cholmod") return std::make_unique<CholmodSolver>();
  throw Error("unknown solver '" + name + "' (expected cg, cg-ichol or cholmod)");
}

}  // namespace trivar
