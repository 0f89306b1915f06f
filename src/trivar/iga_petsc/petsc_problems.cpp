#include "trivar/iga_petsc/petsc_problems.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <tuple>

#include <petscksp.h>
#include <slepceps.h>

#include "trivar/core/error.hpp"
#include "trivar/iga/multipatch_assembly.hpp"
#include "trivar/iga/refined_elasticity.hpp"
#include "trivar/iga/refined_poisson.hpp"
#include "trivar/iga_petsc/petsc_session.hpp"
#include "trivar/iga_petsc/petsc_system.hpp"

namespace trivar {

ElementPartition rank_partition() {
  require(petsc_session_active(), "petsc: no PETSc session is running");
  ElementPartition p;
  MPI_Comm_rank(PETSC_COMM_WORLD, &p.part);
  MPI_Comm_size(PETSC_COMM_WORLD, &p.parts);
  return p;
}

namespace {

PhaseCpuSeconds last_cpu;

double cpu_now() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// A phase's wall clock and processor clock together.
struct Clock {
  using time_point = std::pair<std::chrono::steady_clock::time_point, double>;
  static time_point now() { return {std::chrono::steady_clock::now(), cpu_now()}; }
};

// Wall seconds since t0 (slowest rank); the phase's processor seconds go to `cpu`.
double seconds_since(Clock::time_point t0, double& cpu) {
  cpu = max_over_ranks(cpu_now() - t0.second);
  return max_over_ranks(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0.first).count());
}

// Checked before anything is assembled, so a bad name costs nothing.
void check_preconditioner(const PetscSolverOptions& o) {
  const std::string& p = o.preconditioner;
  require(p == "gamg" || p == "hypre" || p == "bjacobi" || p == "jacobi" || p == "mumps",
          "petsc: unknown preconditioner '" + p + "' (gamg, hypre, bjacobi, jacobi or mumps)");
  require(o.tolerance > 0 && o.tolerance < 1, "petsc: the tolerance must lie in (0, 1)");
}

// Conjugate gradients (or, for mumps, one direct solve) with the named preconditioner.
void configure(KSP ksp, const PetscSolverOptions& o) {
  PC pc;
  petsc_check(KSPGetPC(ksp, &pc), "KSPGetPC");
  const std::string& p = o.preconditioner;
  if (p == "mumps") {
    petsc_check(KSPSetType(ksp, KSPPREONLY), "KSPSetType");
    petsc_check(PCSetType(pc, PCCHOLESKY), "PCSetType");
    petsc_check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
  } else {
    petsc_check(KSPSetType(ksp, KSPCG), "KSPSetType");
    // The same stopping test as the serial CG: the true (unpreconditioned) relative residual.
    petsc_check(KSPSetNormType(ksp, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
    petsc_check(KSPSetTolerances(ksp, o.tolerance, 0.0, PETSC_DEFAULT, 100000), "KSPSetTolerances");
    if (p == "gamg") {
      petsc_check(PCSetType(pc, PCGAMG), "PCSetType");
    } else if (p == "hypre") {
      petsc_check(PCSetType(pc, PCHYPRE), "PCSetType");
      petsc_check(PCHYPRESetType(pc, "boomeramg"), "PCHYPRESetType");
    } else if (p == "bjacobi") {
      petsc_check(PCSetType(pc, PCBJACOBI), "PCSetType");
    } else {
      petsc_check(PCSetType(pc, PCJACOBI), "PCSetType");
    }
  }
  petsc_check(KSPSetFromOptions(ksp), "KSPSetFromOptions");
}

// After the operators are set: incomplete Cholesky in every Jacobi block (shifted to stay positive definite,
// as ICC(0) of an elasticity block can break down otherwise).
void set_up_blocks(KSP ksp, const PetscSolverOptions& o) {
  if (o.preconditioner != "bjacobi") return;
  petsc_check(KSPSetUp(ksp), "KSPSetUp");
  PC pc;
  petsc_check(KSPGetPC(ksp, &pc), "KSPGetPC");
  PetscInt blocks = 0;
  KSP* sub = nullptr;
  petsc_check(PCBJacobiGetSubKSP(pc, &blocks, nullptr, &sub), "PCBJacobiGetSubKSP");
  for (PetscInt i = 0; i < blocks; ++i) {
    PC sub_pc;
    petsc_check(KSPSetType(sub[i], KSPPREONLY), "KSPSetType");
    petsc_check(KSPGetPC(sub[i], &sub_pc), "KSPGetPC");
    petsc_check(PCSetType(sub_pc, PCICC), "PCSetType");
    petsc_check(PCFactorSetShiftType(sub_pc, MAT_SHIFT_POSITIVE_DEFINITE), "PCFactorSetShiftType");
  }
}

// The rigid-body modes of the owned blocks as GAMG's near null space of an elasticity matrix; coordinates: the
// basis functions' control points (D per global function).
template <int D>
void set_rigid_body_modes(Mat A, const DofLayout& L, const std::vector<double>& control) {
  Vec coords;
  petsc_check(VecCreateMPI(PETSC_COMM_WORLD, L.local_rows(), L.size, &coords), "VecCreateMPI");
  petsc_check(VecSetBlockSize(coords, D), "VecSetBlockSize");
  for (int G = 0; G < L.num_basis; ++G) {
    const PetscInt row = L.row(G);
    if (row < L.begin || row >= L.end) continue;
    for (int k = 0; k < D; ++k)
      petsc_check(VecSetValue(coords, row + k, control[static_cast<std::size_t>(D * G + k)], INSERT_VALUES), "VecSetValue");
  }
  petsc_check(VecAssemblyBegin(coords), "VecAssemblyBegin");
  petsc_check(VecAssemblyEnd(coords), "VecAssemblyEnd");
  MatNullSpace modes;
  petsc_check(MatNullSpaceCreateRigidBody(coords, &modes), "MatNullSpaceCreateRigidBody");
  petsc_check(MatSetNearNullSpace(A, modes), "MatSetNearNullSpace");
  petsc_check(MatNullSpaceDestroy(&modes), "MatNullSpaceDestroy");
  petsc_check(VecDestroy(&coords), "VecDestroy");
}

// The control points of a multipatch space's global functions (D per function).
template <int D>
std::vector<double> global_control_points(const MultipatchSpace<D>& space) {
  std::vector<double> control(static_cast<std::size_t>(space.num_basis) * D);
  for (int p = 0; p < space.num_patches(); ++p) {
    const std::vector<int>& g = space.global[static_cast<std::size_t>(p)];
    for (std::size_t i = 0; i < g.size(); ++i)
      space.patches[static_cast<std::size_t>(p)].geometry.control_point(static_cast<int>(i),
                                                                          &control[static_cast<std::size_t>(D * g[i])]);
  }
  return control;
}

// The static problems' common end (solve_constrained in poisson.cpp, distributed): this rank's rows `local` of
// A and its share of the load, the fixed dofs, the solve. near_null (may be null) gives GAMG its near null space.
SolveResult solve_assembled(SparseMatrix& local, Eigen::VectorXd& b_local, const FixedDofs& fixed, int num_basis, int m,
                            bool rows_complete, const std::function<void(Mat, const DofLayout&)>& near_null,
                            const PetscSolverOptions& o, Clock::time_point t0) {
  const DofLayout L = dof_layout(local, num_basis, m);
  Mat A = distributed_matrix(local, L, rows_complete);
  Vec b = distributed_vector(b_local, L);
  b_local = Eigen::VectorXd();
  apply_dirichlet(A, b, fixed, L);
  if (near_null && o.preconditioner == "gamg") near_null(A, L);
  SolveResult r;
  r.assembly_seconds = seconds_since(t0, last_cpu.assembly);
  const auto t1 = Clock::now();
  KSP ksp;
  petsc_check(KSPCreate(PETSC_COMM_WORLD, &ksp), "KSPCreate");
  petsc_check(KSPSetOperators(ksp, A, A), "KSPSetOperators");
  configure(ksp, o);
  set_up_blocks(ksp, o);
  Vec x;
  petsc_check(VecDuplicate(b, &x), "VecDuplicate");
  petsc_check(KSPSolve(ksp, b, x), "KSPSolve");
  KSPConvergedReason reason;
  petsc_check(KSPGetConvergedReason(ksp, &reason), "KSPGetConvergedReason");
  PetscInt its = 0;
  petsc_check(KSPGetIterationNumber(ksp, &its), "KSPGetIterationNumber");
  PetscReal rnorm = 0, bnorm = 0;
  petsc_check(KSPGetResidualNorm(ksp, &rnorm), "KSPGetResidualNorm");
  petsc_check(VecNorm(b, NORM_2, &bnorm), "VecNorm");
  require(reason > 0, "petsc: conjugate gradients with " + o.preconditioner + " did not converge (" +
                          KSPConvergedReasons[reason] + " after " + std::to_string(its) + " iterations)");
  r.solve_seconds = seconds_since(t1, last_cpu.solve);
  r.coefs = gather(x, L);
  r.stats.iterations = static_cast<int>(its);
  r.stats.residual = bnorm > 0 ? rnorm / bnorm : 0.0;
  r.dofs = fixed.num_free();
  petsc_check(KSPDestroy(&ksp), "KSPDestroy");
  petsc_check(VecDestroy(&x), "VecDestroy");
  petsc_check(VecDestroy(&b), "VecDestroy");
  petsc_check(MatDestroy(&A), "MatDestroy");
  return r;
}

// On a multipatch space: loads of this rank's elements (face loads: rank 0, they are boundary integrals), the
// conditions, the rigid-body modes of elasticity.
template <int D>
SolveResult solve_distributed(const MultipatchSpace<D>& space, SparseMatrix& local, int m,
                              const std::function<void(const double*, double*)>& f, const std::vector<Face>& faces,
                              const std::function<void(const double*, const double*, double*)>& g,
                              const std::vector<DirichletCondition<D>>& conditions, const PetscSolverOptions& o,
                              Clock::time_point t0) {
  const ElementPartition part = rank_partition();
  Eigen::VectorXd b_local = on_every_rank([&] {
    Eigen::VectorXd b = f ? assemble_load<D>(space, m, f, o.threads, part)
                          : Eigen::VectorXd::Zero(static_cast<Eigen::Index>(space.num_basis) * m);
    if (part.part == 0 && g && !faces.empty()) add_face_load<D>(space, faces, m, g, b);
    return b;
  });
  const FixedDofs fixed = on_every_rank([&] { return project_dirichlet(space, m, conditions); });
  std::function<void(Mat, const DofLayout&)> near_null;
  if (m == D && m > 1)
    near_null = [&](Mat A, const DofLayout& L) { set_rigid_body_modes<D>(A, L, global_control_points(space)); };
  return solve_assembled(local, b_local, fixed, space.num_basis, m, space.num_patches() == 1, near_null, o, t0);
}

// The free rows of K and M (owned by this rank) and the lowest `count` eigenpairs of the pencil there.
ModesResult modes_distributed(SparseMatrix& K_local, SparseMatrix& M_local, int num_basis, bool one_patch, int m,
                              const FixedDofs& fixed, int count, bool elastic, const PetscSolverOptions& o,
                              Clock::time_point t0) {
  const DofLayout L = dof_layout(K_local, num_basis, m);
  Mat K = distributed_matrix(K_local, L, one_patch), M = distributed_matrix(M_local, L, one_patch);
  // The free rows in PETSc's numbering; their positions in the reduced system follow in the same order.
  std::vector<PetscInt> free_rows;
  for (std::size_t i = 0; i < fixed.fixed.size(); ++i) {
    const PetscInt row = L.row(static_cast<int>(i));
    if (!fixed.fixed[i] && row >= L.begin && row < L.end) free_rows.push_back(row);
  }
  std::sort(free_rows.begin(), free_rows.end());
  IS rows;
  petsc_check(ISCreateGeneral(PETSC_COMM_WORLD, static_cast<PetscInt>(free_rows.size()), free_rows.data(),
                              PETSC_COPY_VALUES, &rows),
              "ISCreateGeneral");
  Mat Kf, Mf;
  petsc_check(MatCreateSubMatrix(K, rows, rows, MAT_INITIAL_MATRIX, &Kf), "MatCreateSubMatrix");
  petsc_check(MatCreateSubMatrix(M, rows, rows, MAT_INITIAL_MATRIX, &Mf), "MatCreateSubMatrix");
  double sigma = 0.0;
  if (elastic) {
    Vec d;
    PetscScalar kt = 0, mt = 0;
    petsc_check(MatCreateVecs(K, &d, nullptr), "MatCreateVecs");
    petsc_check(MatGetDiagonal(K, d), "MatGetDiagonal");
    petsc_check(VecSum(d, &kt), "VecSum");
    petsc_check(MatGetDiagonal(M, d), "MatGetDiagonal");
    petsc_check(VecSum(d, &mt), "VecSum");
    petsc_check(VecDestroy(&d), "VecDestroy");
    sigma = rigid_body_shift(kt, mt);
  }
  petsc_check(MatDestroy(&K), "MatDestroy");
  petsc_check(MatDestroy(&M), "MatDestroy");
  PetscInt n = 0;
  petsc_check(MatGetSize(Kf, &n, nullptr), "MatGetSize");
  require(count >= 1 && count < n, "modes: asked for " + std::to_string(count) + " modes of a problem with " +
                                       std::to_string(n) + " free dofs");
  ModesResult r;
  r.dofs = static_cast<int>(n);
  r.assembly_seconds = seconds_since(t0, last_cpu.assembly);
  const auto t1 = Clock::now();
  EPS eps;
  petsc_check(EPSCreate(PETSC_COMM_WORLD, &eps), "EPSCreate");
  petsc_check(EPSSetOperators(eps, Kf, Mf), "EPSSetOperators");
  petsc_check(EPSSetProblemType(eps, EPS_GHEP), "EPSSetProblemType");
  // A margin of extra pairs, as in lowest_modes: multiple eigenvalues (the cube's) are all found.
  const PetscInt wanted = std::min<PetscInt>(n - 1, count + std::max(6, count / 2));
  petsc_check(EPSSetDimensions(eps, wanted, PETSC_DEFAULT, PETSC_DEFAULT), "EPSSetDimensions");
  petsc_check(EPSSetTolerances(eps, 1e-12, 1000), "EPSSetTolerances");
  petsc_check(EPSSetTarget(eps, sigma), "EPSSetTarget");
  petsc_check(EPSSetWhichEigenpairs(eps, EPS_TARGET_MAGNITUDE), "EPSSetWhichEigenpairs");
  ST st;
  petsc_check(EPSGetST(eps, &st), "EPSGetST");
  petsc_check(STSetType(st, STSINVERT), "STSetType");
  KSP ksp;
  petsc_check(STGetKSP(st, &ksp), "STGetKSP");
  configure(ksp, o);
  petsc_check(EPSSetFromOptions(eps), "EPSSetFromOptions");
  petsc_check(EPSSolve(eps), "EPSSolve");
  PetscInt converged = 0;
  petsc_check(EPSGetConverged(eps, &converged), "EPSGetConverged");
  require(converged >= count, "modes: SLEPc converged " + std::to_string(converged) + " of " +
                                  std::to_string(count) + " eigenpairs");
  Vec xr, Mx;
  petsc_check(MatCreateVecs(Kf, &xr, &Mx), "MatCreateVecs");
  IS all_rows;
  petsc_check(ISAllGather(rows, &all_rows), "ISAllGather");
  const PetscInt* where = nullptr;
  petsc_check(ISGetIndices(all_rows, &where), "ISGetIndices");
  std::vector<std::pair<double, PetscInt>> order;
  for (PetscInt i = 0; i < converged; ++i) {
    PetscScalar kr = 0;
    petsc_check(EPSGetEigenvalue(eps, i, &kr, nullptr), "EPSGetEigenvalue");
    order.emplace_back(kr, i);
  }
  std::sort(order.begin(), order.end());
  r.values.resize(count);
  r.vectors = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(fixed.fixed.size()), count);
  std::vector<double> by_row(static_cast<std::size_t>(L.size));
  for (int i = 0; i < count; ++i) {
    PetscScalar kr = 0;
    petsc_check(EPSGetEigenpair(eps, order[static_cast<std::size_t>(i)].second, &kr, nullptr, xr, nullptr),
                "EPSGetEigenpair");
    r.values[i] = kr;
    // M-normalised, as lowest_modes returns them.
    PetscScalar xMx = 0;
    petsc_check(MatMult(Mf, xr, Mx), "MatMult");
    petsc_check(VecDot(xr, Mx, &xMx), "VecDot");
    petsc_check(VecScale(xr, 1.0 / std::sqrt(xMx)), "VecScale");
    VecScatter scatter;
    Vec all;
    petsc_check(VecScatterCreateToAll(xr, &scatter, &all), "VecScatterCreateToAll");
    petsc_check(VecScatterBegin(scatter, xr, all, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
    petsc_check(VecScatterEnd(scatter, xr, all, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
    const PetscScalar* v = nullptr;
    petsc_check(VecGetArrayRead(all, &v), "VecGetArrayRead");
    std::fill(by_row.begin(), by_row.end(), 0.0);
    for (PetscInt k = 0; k < n; ++k) by_row[static_cast<std::size_t>(where[k])] = v[k];
    petsc_check(VecRestoreArrayRead(all, &v), "VecRestoreArrayRead");
    for (Eigen::Index dof = 0; dof < r.vectors.rows(); ++dof)
      r.vectors(dof, i) = by_row[static_cast<std::size_t>(L.row(static_cast<int>(dof)))];
    petsc_check(VecScatterDestroy(&scatter), "VecScatterDestroy");
    petsc_check(VecDestroy(&all), "VecDestroy");
  }
  r.solve_seconds = seconds_since(t1, last_cpu.solve);
  petsc_check(ISRestoreIndices(all_rows, &where), "ISRestoreIndices");
  petsc_check(ISDestroy(&all_rows), "ISDestroy");
  petsc_check(ISDestroy(&rows), "ISDestroy");
  petsc_check(VecDestroy(&xr), "VecDestroy");
  petsc_check(VecDestroy(&Mx), "VecDestroy");
  petsc_check(EPSDestroy(&eps), "EPSDestroy");
  petsc_check(MatDestroy(&Kf), "MatDestroy");
  petsc_check(MatDestroy(&Mf), "MatDestroy");
  return r;
}

// The norms of the whole domain from each rank's part (squares add).
ErrorNorms sum_over_ranks(const ErrorNorms& mine) {
  double squares[2] = {mine.l2 * mine.l2, mine.h1 * mine.h1};
  MPI_Allreduce(MPI_IN_PLACE, squares, 2, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  return {std::sqrt(squares[0]), std::sqrt(squares[1])};
}

}  // namespace

const PhaseCpuSeconds& last_phase_cpu_seconds() { return last_cpu; }

template <int D>
SolveResult petsc_solve_poisson(const MultipatchSpace<D>& space, const PoissonProblem<D>& problem,
                                const PetscSolverOptions& o) {
  check_preconditioner(o);
  const auto t0 = Clock::now();
  const BilinearForm<D> form = poisson_form(problem);
  SparseMatrix local =
      on_every_rank([&] { return assemble_matrix<D>(space, [&](int) { return form; }, o.threads, rank_partition()); });
  std::function<void(const double*, double*)> f;
  if (problem.source) f = [&](const double* x, double* out) { out[0] = problem.source(x); };
  std::function<void(const double*, const double*, double*)> g;
  if (problem.flux) g = [&](const double* x, const double* n, double* out) { out[0] = problem.flux(x, n); };
  return solve_distributed<D>(space, local, 1, f, problem.neumann, g, problem.dirichlet, o, t0);
}

template <int D>
SolveResult petsc_solve_elasticity(const MultipatchSpace<D>& space, const ElasticityProblem<D>& problem,
                                   const PetscSolverOptions& o) {
  check_preconditioner(o);
  const auto t0 = Clock::now();
  SparseMatrix local = on_every_rank([&] { return elastic_stiffness(space, problem, o.threads, rank_partition()); });
  return solve_distributed<D>(space, local, D, problem.body_force, problem.traction_faces, problem.traction,
                              problem.displacement, o, t0);
}

template <int D>
ModesResult petsc_laplace_modes(const MultipatchSpace<D>& space, const std::vector<Face>& dirichlet, int count,
                                const PetscSolverOptions& o) {
  check_preconditioner(o);
  const auto t0 = Clock::now();
  const BilinearForm<D> stiffness = poisson_form(PoissonProblem<D>{}), mass = scalar_mass_form<D>();
  auto [K, M, fixed] = on_every_rank([&] {
    return std::tuple{assemble_matrix<D>(space, [&](int) { return stiffness; }, o.threads, rank_partition()),
                      assemble_matrix<D>(space, [&](int) { return mass; }, o.threads, rank_partition()),
                      project_dirichlet<D>(space, 1, {{dirichlet, {}, nullptr}})};
  });
  return modes_distributed(K, M, space.num_basis, space.num_patches() == 1, 1, fixed, count, false, o, t0);
}

template <int D>
ModesResult petsc_elastic_modes(const MultipatchSpace<D>& space, const ElasticityProblem<D>& problem, int count,
                                const PetscSolverOptions& o) {
  check_preconditioner(o);
  const auto t0 = Clock::now();
  auto [K, M, fixed] = on_every_rank([&] {
    return std::tuple{elastic_stiffness(space, problem, o.threads, rank_partition()),
                      elastic_mass(space, problem, o.threads, rank_partition()),
                      project_dirichlet(space, D, problem.displacement)};
  });
  return modes_distributed(K, M, space.num_basis, space.num_patches() == 1, D, fixed, count, true, o, t0);
}

template <int D>
ErrorNorms petsc_error_norms(const MultipatchSpace<D>& space, const Eigen::VectorXd& coefs, int components,
                             const ExactSolution<D>& exact, int threads) {
  return sum_over_ranks(
      on_every_rank([&] { return error_norms(space, coefs, components, exact, threads, rank_partition()); }));
}

template <int D>
SolveResult petsc_solve_poisson(const RefinedSpace<D>& space, const PoissonProblem<D>& problem,
                                const PetscSolverOptions& o) {
  check_preconditioner(o);
  const auto t0 = Clock::now();
  auto [A, b] = on_every_rank([&] { return poisson_system(space, problem, o.threads, rank_partition()); });
  return solve_assembled(A, b, on_every_rank([&] { return refined_fixed_dofs(space, 1, problem.dirichlet); }), space.num_basis, 1, false, nullptr, o,
                         t0);
}

template <int D>
SolveResult petsc_solve_elasticity(const RefinedSpace<D>& space, const ElasticityProblem<D>& problem,
                                   const PetscSolverOptions& o) {
  check_preconditioner(o);
  const auto t0 = Clock::now();
  auto [A, b] = on_every_rank([&] { return elasticity_system(space, problem, o.threads, rank_partition()); });
  const FixedDofs fixed = on_every_rank([&] { return refined_fixed_dofs(space, D, problem.displacement); });
  return solve_assembled(A, b, fixed, space.num_basis, D, false,
                         [&](Mat M, const DofLayout& L) { set_rigid_body_modes<D>(M, L, space.control); }, o, t0);
}

template <int D>
ModesResult petsc_laplace_modes(const RefinedSpace<D>& space, const std::vector<Face>& dirichlet, int count,
                                const PetscSolverOptions& o) {
  check_preconditioner(o);
  const auto t0 = Clock::now();
  ModesPencil p = on_every_rank([&] { return laplace_pencil(space, dirichlet, o.threads, rank_partition()); });
  return modes_distributed(p.K, p.M, space.num_basis, false, 1, p.fixed, count, false, o, t0);
}

template <int D>
ModesResult petsc_elastic_modes(const RefinedSpace<D>& space, const ElasticityProblem<D>& problem, int count,
                                const PetscSolverOptions& o) {
  check_preconditioner(o);
  const auto t0 = Clock::now();
  ModesPencil p = on_every_rank([&] { return elastic_pencil(space, problem, o.threads, rank_partition()); });
  return modes_distributed(p.K, p.M, space.num_basis, false, D, p.fixed, count, true, o, t0);
}

template <int D>
ErrorNorms petsc_error_norms(const RefinedSpace<D>& space, const Eigen::VectorXd& coefs, int components,
                             const ExactSolution<D>& exact, int threads) {
  return sum_over_ranks(
      on_every_rank([&] { return error_norms(space, coefs, components, exact, threads, rank_partition()); }));
}

#define TRIVAR_INSTANTIATE(D)                                                                                    \
  template SolveResult petsc_solve_poisson(const RefinedSpace<D>&, const PoissonProblem<D>&,                     \
                                           const PetscSolverOptions&);                                           \
  template SolveResult petsc_solve_elasticity(const RefinedSpace<D>&, const ElasticityProblem<D>&,               \
                                              const PetscSolverOptions&);                                        \
  template ErrorNorms petsc_error_norms(const RefinedSpace<D>&, const Eigen::VectorXd&, int,                     \
                                        const ExactSolution<D>&, int);                                           \
  template ModesResult petsc_laplace_modes(const RefinedSpace<D>&, const std::vector<Face>&, int,                 \
                                           const PetscSolverOptions&);                                           \
  template ModesResult petsc_elastic_modes(const RefinedSpace<D>&, const ElasticityProblem<D>&, int,              \
                                           const PetscSolverOptions&);                                           \
  template SolveResult petsc_solve_poisson(const MultipatchSpace<D>&, const PoissonProblem<D>&,                   \
                                           const PetscSolverOptions&);                                           \
  template SolveResult petsc_solve_elasticity(const MultipatchSpace<D>&, const ElasticityProblem<D>&,             \
                                              const PetscSolverOptions&);                                        \
  template ModesResult petsc_laplace_modes(const MultipatchSpace<D>&, const std::vector<Face>&, int,              \
                                           const PetscSolverOptions&);                                           \
  template ModesResult petsc_elastic_modes(const MultipatchSpace<D>&, const ElasticityProblem<D>&, int,           \
                                           const PetscSolverOptions&);                                           \
  template ErrorNorms petsc_error_norms(const MultipatchSpace<D>&, const Eigen::VectorXd&, int,                   \
                                        const ExactSolution<D>&, int);
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

}  // namespace trivar
