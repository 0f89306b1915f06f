#include "trivar/iga/adaptive_loop.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "trivar/core/error.hpp"
#include "trivar/iga/benchmark_problems.hpp"
#include "trivar/iga/refined_poisson.hpp"
#include "iga/iga_test_support.hpp"

using namespace trivar;

namespace {

// `steps` adaptive solves (Dorfler fraction 0.3) from the benchmark's space, each adding dofs and lowering the
// error, with an estimate that tracks it.
std::vector<ConvergenceRow> adapt(const PoissonBenchmark<2>& b, int steps) {
  LRSpline<2> lr(b.space.geometry);
  AdaptiveOptions o;
  o.steps = steps;
  o.beta = 0.3;
  const auto rows = adaptive_poisson(lr, b.problem, b.exact, o);
  EXPECT_EQ(rows.size(), static_cast<std::size_t>(steps));
  iga_test::expect_monotone_and_efficient(rows);
  return rows;
}

}  // namespace

TEST(LRPoisson, MatchesTheTensorSolverOnAnUnrefinedSpace) {
  // An LR spline converted from a tensor spline has the same basis: same dofs, same errors.
  const PoissonBenchmark<2> b = sine_box<2>(2, 6);
  auto solver = make_solver("cholmod");
  const SolveResult tr = solve_poisson(b.space, b.problem, *solver);
  const ErrorNorms te = error_norms<2>(b.space, tr.coefs, 1, b.exact);
  const LRSpline<2> lr(b.space.geometry);
  const auto space = refined_space(lr);
  const SolveResult r = solve_poisson(space, b.problem, *solver);
  EXPECT_EQ(r.dofs, tr.dofs);
  const ErrorNorms e = error_norms<2>(space, r.coefs, 1, b.exact);
  EXPECT_NEAR(e.l2, te.l2, 1e-9 * te.l2);
  EXPECT_NEAR(e.h1, te.h1, 1e-9 * te.h1);
}

TEST(LRPoisson, LShapeUniformRefinementIsLimitedBySingularity) {
  // u ~ r^(2/3): H1 error ~ h^(2/3) under uniform refinement, whatever the degree.
  ErrorNorms prev;
  for (int n : {4, 8, 16}) {
    const PoissonBenchmark<2> b = l_shape(2, n);
    auto solver = make_solver("cholmod");
    const SolveResult r = solve_poisson(b.space, b.problem, *solver);
    const ErrorNorms e = error_norms<2>(b.space, r.coefs, 1, b.exact);
    if (n > 4) {
      EXPECT_NEAR(std::log2(prev.h1 / e.h1), 2.0 / 3.0, 0.12) << n;
    }
    prev = e;
  }
}

TEST(Adaptive, LShapeAdaptiveLRBeatsUniformRefinement) {
  // Dorfler marking with the residual indicator refines towards the corner: the error falls at the optimal
  // rate dofs^(-p/2) for p = 2 (H1) instead of dofs^(-1/3), so the adaptive error at the last step is
  // reached by uniform refinement only with several times more dofs.
  const PoissonBenchmark<2> b = l_shape(2, 4);
  const auto rows = adapt(b, 8);
  // Uniform refinement: H1 error ~ C dofs^(-1/3); C from a uniform solve.
  const PoissonBenchmark<2> u = l_shape(2, 16);
  auto solver = make_solver("cholmod");
  const SolveResult ur = solve_poisson(u.space, u.problem, *solver);
  const double eu = error_norms<2>(u.space, ur.coefs, 1, u.exact).h1;
  const double dofs_uniform = ur.dofs * std::pow(eu / rows.back().h1, 3.0);
  EXPECT_GT(dofs_uniform, 3.0 * rows.back().dofs);
  LRSpline<2> lr(b.space.geometry);
  EXPECT_THROW(adaptive_poisson(lr, b.problem, b.exact, {0, 0.3, {}, "cholmod"}), Error);
  EXPECT_THROW(adaptive_poisson(lr, b.problem, b.exact, {2, 1.5, {}, "cholmod"}), Error);
}

TEST(Adaptive, LShapeWithNeumannDataOnTheOuterBoundary) {
  // The l-shape with the exact flux du/dn as Neumann data on the outer boundary (side v = 1: the edges y = 1
  // and x = -1) and Dirichlet data elsewhere. The indicator's Neumann term stands in for the boundary values
  // there; the loop still reaches the optimal H1 rate dofs^(-p/2) = dofs^(-1) and the estimate tracks the
  // error.
  PoissonBenchmark<2> b = l_shape(2, 4);
  const ExactSolution<2> exact = b.exact;
  b.problem.dirichlet[0].faces = {{0, 0}, {0, 1}, {1, 0}};
  b.problem.neumann = {{1, 1}};
  b.problem.flux = [exact](const double* x, const double* n) {
    double u, g[2];
    exact(x, &u, g);
    return g[0] * n[0] + g[1] * n[1];
  };
  const auto rows = adapt(b, 9);
  const auto& first = rows[rows.size() - 4];
  const auto& last = rows.back();
  const double rate = std::log(first.h1 / last.h1) / std::log(static_cast<double>(last.dofs) / first.dofs);
  EXPECT_GT(rate, 0.8);
}
