#include <gtest/gtest.h>

#include <cmath>

#include "iga/iga_test_support.hpp"
#include "trivar/iga/benchmark_problems.hpp"
#include "trivar/iga/refined_elasticity.hpp"
#include "trivar/iga/refined_poisson.hpp"
#include "trivar/iga_petsc/petsc_problems.hpp"
#include "trivar/lr/lr_spline.hpp"

// Locally refined (LR) spaces on the ranks against the serial solve (CHOLMOD): the same errors to 1e-10.

using namespace trivar;

namespace {

PetscSolverOptions tight(const std::string& pc) {
  PetscSolverOptions o;
  o.preconditioner = pc;
  o.tolerance = 1e-13;
  return o;
}

}  // namespace

TEST(PetscRefined, PoissonOnALocallyRefinedSineCubeMatchesTheSerialSolve) {
  // T-junctions inside the cube: elements of one rank and the other share functions of every size.
  const PoissonBenchmark<3> b = sine_box<3>(2, 4);
  LRSpline<3> lr(b.space.geometry);
  iga_test::refine_corner(lr, 0.5);
  iga_test::refine_corner(lr, 0.25);
  ASSERT_TRUE(iga_test::has_t_junction(lr));
  const RefinedSpace<3> space = refined_space(lr);
  auto serial = make_solver("cholmod");
  const SolveResult s = solve_poisson(space, b.problem, *serial);
  const ErrorNorms es = error_norms(space, s.coefs, 1, b.exact);
  for (const char* pc : {"gamg", "bjacobi"}) {
    SCOPED_TRACE(pc);
    const SolveResult d = petsc_solve_poisson(space, b.problem, tight(pc));
    EXPECT_EQ(d.dofs, s.dofs);
    const ErrorNorms ed = petsc_error_norms(space, d.coefs, 1, b.exact);
    EXPECT_LE(std::abs(ed.l2 - es.l2), 1e-10 * es.l2);
    EXPECT_LE(std::abs(ed.h1 - es.h1), 1e-10 * es.h1);
  }
}

TEST(PetscRefined, ElasticityOnALocallyRefinedBeamMatchesTheSerialSolve) {
  // A 2 x 1 beam clamped at x = 0 under gravity and a shear traction at x = 2 (element side loads of each
  // rank's elements): the same displacements as the serial solve.
  LRSpline<2> lr(box_geometry<2>({0, 0}, {2, 1}, 2, 4));
  iga_test::refine_corner(lr, 0.5);
  const RefinedSpace<2> space = refined_space(lr);
  ElasticityProblem<2> pb;
  pb.material = {1000.0, 0.3, 1.0};
  pb.body_force = [](const double*, double* f) { f[0] = 0, f[1] = -1; };
  pb.displacement = {{{Face{0, 0, 0}}, {}, nullptr}};
  pb.traction_faces = {Face{0, 1, 0}};
  pb.traction = [](const double* x, const double*, double* t) { t[0] = 0, t[1] = -x[1]; };
  auto serial = make_solver("cholmod");
  const SolveResult s = solve_elasticity(space, pb, *serial);
  const SolveResult d = petsc_solve_elasticity(space, pb, tight("gamg"));
  EXPECT_EQ(d.dofs, s.dofs);
  EXPECT_LE((d.coefs - s.coefs).norm(), 1e-10 * s.coefs.norm());
}
