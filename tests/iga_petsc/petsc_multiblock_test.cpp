#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "trivar/fit/multiblock_adaptive.hpp"
#include "trivar/iga/benchmark_problems.hpp"
#include "trivar/iga/refined_poisson.hpp"
#include "trivar/iga/tensor_space.hpp"
#include "trivar/iga_petsc/petsc_problems.hpp"

// Multi-block models with T-joints (fit/multiblock_space) on the ranks against the serial solve: the same errors to
// 1e-10, and the adaptive loop (estimate, marking, refinement inside the blocks, matching again) taking the ranks'
// solves through the same steps.

using namespace trivar;

namespace {

// The L-shape [-1, 1]^2 minus [0, 1] x [-1, 0]: the left column and two blocks on the upper half of its right side
// (T-joints at (0, 0) and (0, 1/2)), 3, 2 and 4 biquadratic elements per direction.
std::vector<LRSpline<2>> t_joint_l_shape() {
  return {LRSpline<2>(box_geometry<2>({-1, -1}, {0, 1}, 2, 3)), LRSpline<2>(box_geometry<2>({0, 0}, {1, 0.5}, 2, 2)),
          LRSpline<2>(box_geometry<2>({0, 0.5}, {1, 1}, 2, 4))};
}

PetscSolverOptions direct_options() {
  PetscSolverOptions o;
  o.preconditioner = "mumps";
  o.tolerance = 1e-13;
  return o;
}

}  // namespace

TEST(PetscMultiblock, TJointLShapeMatchesTheSerialSolveAndAdaptiveLoop) {
  const ExactSolution<2> exact = l_shape(2, 1).exact;
  MultiblockSpace<2> m = multiblock_space(t_joint_l_shape());
  PoissonProblem<2> pb;
  pb.dirichlet.push_back({boundary_faces(m), {}, [exact](const double* x, double* u) {
                            double g[2];
                            exact(x, u, g);
                          }});
  auto serial = make_solver("cholmod");
  const SolveResult s = solve_poisson(m.space, pb, *serial, 1);
  const ErrorNorms es = error_norms(m.space, s.coefs, 1, exact, 1);
  for (const char* pc : {"mumps", "gamg"}) {
    SCOPED_TRACE(pc);
    PetscSolverOptions o = direct_options();
    o.preconditioner = pc;
    const SolveResult d = petsc_solve_poisson(m.space, pb, o);
    EXPECT_EQ(d.dofs, s.dofs);
    const ErrorNorms ed = petsc_error_norms(m.space, d.coefs, 1, exact);
    EXPECT_LE(std::abs(ed.l2 - es.l2), 1e-10 * es.l2);
    EXPECT_LE(std::abs(ed.h1 - es.h1), 1e-10 * es.h1);
  }
  AdaptiveOptions a;
  a.steps = 3;
  MultiblockSpace<2> ms = m;
  const std::vector<ConvergenceRow> want = adaptive_poisson(ms, pb, exact, a, {}, nullptr, 1);
  const RefinedPoissonSolve<2> ranks = [](const RefinedSpace<2>& space, const PoissonProblem<2>& p) {
    return petsc_solve_poisson(space, p, direct_options());
  };
  const std::vector<ConvergenceRow> got = adaptive_poisson(m, pb, exact, a, {}, nullptr, 1, ranks);
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].dofs, want[i].dofs);
    EXPECT_EQ(got[i].elements, want[i].elements);
    EXPECT_NEAR(got[i].h1, want[i].h1, 1e-10 * want[i].h1);
    EXPECT_NEAR(got[i].estimate, want[i].estimate, 1e-9 * want[i].estimate);
  }
  EXPECT_GT(got.back().elements, got.front().elements);
}
