#include <gtest/gtest.h>

#include <cmath>

#include "trivar/core/error.hpp"
#include "trivar/iga/benchmark_problems.hpp"
#include "trivar/iga/eigen_modes.hpp"
#include "trivar/iga/elasticity.hpp"
#include "trivar/iga/error_norms.hpp"
#include "trivar/iga/poisson.hpp"
#include "trivar/iga_petsc/petsc_problems.hpp"
#include "trivar/iga_petsc/petsc_session.hpp"
#include "trivar/model/ball.hpp"
#include "trivar/model/vmodel.hpp"

// Every test compares the distributed solve (all ranks of the session, two under ctest) with the serial one
// (CHOLMOD, an independent direct factorisation): the same errors and eigenvalues to 1e-10 relative.

using namespace trivar;

namespace {

void expect_relative(double a, double b, double tol = 1e-10) { EXPECT_LE(std::abs(a - b), tol * std::abs(b)) << a << " vs " << b; }

PetscSolverOptions tight(const std::string& pc) {
  PetscSolverOptions o;
  o.preconditioner = pc;
  o.tolerance = 1e-13;
  return o;
}

// The seven-cell ball: rational patches of different orientations glued into one multipatch space.
MultipatchSpace<3> ball_space(int degree, int elements) {
  BallSpec spec;
  spec.radius = 1.5;
  VModel m;
  for (const auto& c : make_ball(spec)) m.add_cell(VCell(c));
  m.glue();
  return multipatch_space(m, degree, elements);
}

}  // namespace

TEST(PetscPoisson, SineCubeMatchesTheSerialSolveForEveryPreconditioner) {
  const PoissonBenchmark<3> b = sine_box<3>(2, 6);
  const MultipatchSpace<3> space = single_patch_space(b.space);
  auto serial = make_solver("cholmod");
  const SolveResult s = solve_poisson(space, b.problem, *serial);
  const ErrorNorms es = error_norms(space, s.coefs, 1, b.exact);
  for (const char* pc : {"gamg", "hypre", "bjacobi", "jacobi", "mumps"}) {
    SCOPED_TRACE(pc);
    const SolveResult d = petsc_solve_poisson(space, b.problem, tight(pc));
    EXPECT_EQ(d.dofs, s.dofs);
    const ErrorNorms ed = petsc_error_norms(space, d.coefs, 1, b.exact);
    expect_relative(ed.l2, es.l2);
    expect_relative(ed.h1, es.h1);
    EXPECT_LT((d.coefs - s.coefs).lpNorm<Eigen::Infinity>(), 1e-10);
    if (std::string(pc) != "mumps") {
      EXPECT_GT(d.stats.iterations, 0);
    }
  }
}

TEST(PetscPoisson, ErrorNormsOfTheRanksSumToTheWhole) {
  // The reduction over ranks against the serial integration of the same coefficients.
  const PoissonBenchmark<2> b = sine_box<2>(3, 7);
  const MultipatchSpace<2> space = single_patch_space(b.space);
  auto serial = make_solver("cholmod");
  const Eigen::VectorXd c = solve_poisson(space, b.problem, *serial).coefs;
  const ErrorNorms whole = error_norms(space, c, 1, b.exact), reduced = petsc_error_norms(space, c, 1, b.exact);
  expect_relative(reduced.l2, whole.l2, 1e-13);
  expect_relative(reduced.h1, whole.h1, 1e-13);
}

TEST(PetscPoisson, MultipatchBallMatchesTheSerialSolve) {
  // -lap u = 1, u = 0 on the sphere, on seven rational patches: shared interface functions belong to one rank
  // and receive the other rank's element contributions.
  const MultipatchSpace<3> space = ball_space(2, 2);
  PoissonProblem<3> pb;
  pb.source = [](const double*) { return 1.0; };
  pb.dirichlet = {{space.boundary, {}, nullptr}};
  const double R = 1.5;
  const ExactSolution<3> exact = [R](const double* x, double* u, double* g) {
    u[0] = (R * R - x[0] * x[0] - x[1] * x[1] - x[2] * x[2]) / 6;
    for (int k = 0; k < 3; ++k) g[k] = -x[k] / 3;
  };
  auto serial = make_solver("cholmod");
  const SolveResult s = solve_poisson(space, pb, *serial);
  const SolveResult d = petsc_solve_poisson(space, pb, tight("gamg"));
  const ErrorNorms es = error_norms(space, s.coefs, 1, exact), ed = petsc_error_norms(space, d.coefs, 1, exact);
  expect_relative(ed.l2, es.l2);
  expect_relative(ed.h1, es.h1);
}

TEST(PetscElasticity, LameCylinderWithTractionsMatchesTheSerialSolve) {
  // Pressure on the inner face (a face load), symmetry conditions on single components.
  const ElasticityBenchmark<3> b = lame_cylinder<3>(2, 4);
  const MultipatchSpace<3> space = single_patch_space(b.space);
  auto serial = make_solver("cholmod");
  const SolveResult s = solve_elasticity(space, b.problem, *serial);
  const ErrorNorms es = error_norms(space, s.coefs, 3, b.exact);
  for (const char* pc : {"gamg", "hypre", "bjacobi"}) {
    SCOPED_TRACE(pc);
    const SolveResult d = petsc_solve_elasticity(space, b.problem, tight(pc));
    const ErrorNorms ed = petsc_error_norms(space, d.coefs, 3, b.exact);
    expect_relative(ed.l2, es.l2);
    expect_relative(ed.h1, es.h1);
  }
}

TEST(PetscElasticity, PlateWithHoleIn2DMatchesTheSerialSolve) {
  const ElasticityBenchmark<2> b = plate_with_hole(2, 6);
  const MultipatchSpace<2> space = single_patch_space(b.space);
  auto serial = make_solver("cholmod");
  const SolveResult s = solve_elasticity(space, b.problem, *serial);
  const SolveResult d = petsc_solve_elasticity(space, b.problem, tight("gamg"));
  const ErrorNorms es = error_norms(space, s.coefs, 2, b.exact), ed = petsc_error_norms(space, d.coefs, 2, b.exact);
  expect_relative(ed.l2, es.l2);
  expect_relative(ed.h1, es.h1);
}

TEST(PetscElasticity, MultipatchBallUnderGravityMatchesTheSerialSolve) {
  const MultipatchSpace<3> space = ball_space(2, 1);
  ElasticityProblem<3> pb;
  pb.material = {1000.0, 0.3, 1.0};
  pb.body_force = [](const double*, double* f) { f[0] = 0, f[1] = 0, f[2] = -1; };
  pb.displacement = {{space.boundary, {}, nullptr}};
  auto serial = make_solver("cholmod");
  const SolveResult s = solve_elasticity(space, pb, *serial);
  const SolveResult d = petsc_solve_elasticity(space, pb, tight("gamg"));
  EXPECT_LE((d.coefs - s.coefs).norm(), 1e-10 * s.coefs.norm());
}

TEST(PetscModes, CubeLaplaceEigenvaluesMatchTheSerialOnes) {
  // The lowest eigenvalue 3 pi^2 is simple, the next 6 pi^2 triple: all copies are found.
  const MultipatchSpace<3> space = single_patch_space(TensorSpace<3>{box_geometry<3>({0, 0, 0}, {1, 1, 1}, 2, 5)});
  const ModesResult s = laplace_modes(space, space.boundary, 5);
  for (const char* pc : {"mumps", "gamg"}) {
    SCOPED_TRACE(pc);
    const ModesResult d = petsc_laplace_modes(space, space.boundary, 5, tight(pc));
    EXPECT_EQ(d.dofs, s.dofs);
    for (int i = 0; i < 5; ++i) expect_relative(d.values[i], s.values[i]);
    // An M-normalised simple mode is the serial one up to sign.
    const double dot = d.vectors.col(0).dot(s.vectors.col(0)) / (s.vectors.col(0).squaredNorm());
    EXPECT_NEAR(std::abs(dot), 1.0, 1e-8);
  }
}

TEST(PetscModes, RollerCubeElasticEigenvaluesMatchTheSerialOnes) {
  const MultipatchSpace<3> space = single_patch_space(TensorSpace<3>{box_geometry<3>({0, 0, 0}, {1, 1, 1}, 2, 3)});
  ElasticityProblem<3> pb;
  pb.material = {1000.0, 0.3, 1.0};
  for (const Face& f : space.boundary) pb.displacement.push_back({{f}, {f.dir}, nullptr});
  const ModesResult s = elastic_modes(space, pb, 4);
  const ModesResult d = petsc_elastic_modes(space, pb, 4, tight("mumps"));
  for (int i = 0; i < 4; ++i) expect_relative(d.values[i], s.values[i]);
}

TEST(PetscSolver, RefusesAnUnknownPreconditioner) {
  const PoissonBenchmark<2> b = sine_box<2>(2, 2);
  EXPECT_THROW(petsc_solve_poisson(single_patch_space(b.space), b.problem, tight("ilu-magic")), Error);
}
