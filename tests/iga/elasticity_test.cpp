#include "trivar/iga/elasticity.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "iga/iga_test_support.hpp"
#include "trivar/core/error.hpp"
#include "trivar/iga/benchmark_problems.hpp"
#include "trivar/iga/error_norms.hpp"

using namespace trivar;

namespace {

template <int D>
ErrorNorms lame_errors(int p, int n) {
  const ElasticityBenchmark<D> b = lame_cylinder<D>(p, n);
  auto solver = make_solver("cholmod");
  const SolveResult r = solve_elasticity(b.space, b.problem, *solver);
  return error_norms<D>(b.space, r.coefs, D, b.exact);
}

}  // namespace

TEST(Elasticity, LameCylinderConvergesToTheExactSolution) {
  // Exact geometry (NURBS), smooth exact solution: rates p + 1 (L2) and p (H1) in h.
  for (int p : {2, 3}) {
    const ErrorNorms e1 = lame_errors<2>(p, 4), e2 = lame_errors<2>(p, 8), e3 = lame_errors<2>(p, 16);
    EXPECT_GE(std::log2(e2.l2 / e3.l2), p + 1 - 0.2) << p;
    EXPECT_GE(std::log2(e2.h1 / e3.h1), p - 0.2) << p;
    EXPECT_LE(std::log2(e1.h1 / e2.h1), p + 0.7) << p;
  }
  // 3-D slab in plane strain: the same solution; u_z = 0 and the z-independence are reproduced.
  const ErrorNorms e2 = lame_errors<3>(2, 2), e4 = lame_errors<3>(2, 4);
  EXPECT_GE(std::log2(e2.l2 / e4.l2), 3 - 0.3);
  EXPECT_GE(std::log2(e2.h1 / e4.h1), 2 - 0.2);
}

TEST(Elasticity, PlateWithHoleConvergesToKirsch) {
  // Exact geometry, smooth solution: rates p + 1 and p once the steep (a / r)^4 terms at the hole are resolved
  // (measured: L2 rates 1.7, 2.7, 3.2 and H1 rates 1.0, 1.5, 1.8 from 2 to 16).
  auto errors = [](int p, int n) {
    const ElasticityBenchmark<2> b = plate_with_hole(p, n);
    auto solver = make_solver("cholmod");
    const SolveResult r = solve_elasticity(b.space, b.problem, *solver);
    return error_norms<2>(b.space, r.coefs, 2, b.exact);
  };
  const ErrorNorms e4 = errors(2, 4), e8 = errors(2, 8), e16 = errors(2, 16);
  EXPECT_GE(std::log2(e8.l2 / e16.l2), 3 - 0.3);
  EXPECT_GE(std::log2(e8.h1 / e16.h1), 2 - 0.3);
  EXPECT_LT(e16.h1, e4.h1 / 8);
  // Kirsch's stress field itself: the concentration 3 T at the top of the hole, zero traction on the hole.
  double s[3];
  const double top[2] = {0, 1}, side[2] = {1, 0};
  kirsch_stress(10, 1, top, s);
  EXPECT_NEAR(s[0], 30, 1e-12);
  kirsch_stress(10, 1, side, s);
  EXPECT_NEAR(s[0], 0, 1e-12);  // sigma_rr on the hole
  EXPECT_NEAR(s[1], -10, 1e-12);
}

TEST(Elasticity, PatchTestReproducesLinearDisplacement) {
  // A linear displacement field has constant stress: with its Dirichlet data on the start faces and its
  // traction sigma n on the end faces it is the exact discrete solution (polynomial map, exact quadrature:
  // see the Poisson patch test).
  const double G[2][2] = {{0.01, -0.02}, {0.005, 0.03}};
  const ElasticMaterial m{200.0, 0.25};
  auto exact = [G](const double* x, double* u, double* g) {
    for (int i = 0; i < 2; ++i) {
      u[i] = 0.1 * i;
      for (int j = 0; j < 2; ++j) {
        u[i] += G[i][j] * x[j];
        g[i * 2 + j] = G[i][j];
      }
    }
  };
  ElasticityProblem<2> p;
  p.material = m;
  p.displacement.push_back({{{0, 0}, {1, 0}}, {}, [exact](const double* x, double* u) {
                              double g[4];
                              exact(x, u, g);
                            }});
  p.traction_faces = {{0, 1}, {1, 1}};
  p.traction = [m, G](const double*, const double* n, double* t) {
    double s[4];
    stress<2>(m, &G[0][0], s);
    for (int i = 0; i < 2; ++i) t[i] = s[i * 2] * n[0] + s[i * 2 + 1] * n[1];
  };
  const TensorSpace<2> space{iga_test::distorted_box<2>(2, 3, false, 31)};
  auto solver = make_solver("cholmod");
  const SolveResult r = solve_elasticity(space, p, *solver);
  const ErrorNorms e = error_norms<2>(space, r.coefs, 2, exact);
  EXPECT_LE(e.l2, 1e-11);
  EXPECT_LE(e.h1, 1e-10);
}

TEST(Elasticity, StressAndVonMises) {
  // Uniaxial stress sigma_xx = s in 3-D: von Mises = |s|. Pure shear tau: sqrt(3) tau.
  const ElasticMaterial m{210.0, 0.3};
  const double s = 2.0;
  const double grad[9] = {s / m.youngs_modulus, 0, 0, 0, -m.poisson_ratio * s / m.youngs_modulus, 0,
                          0, 0, -m.poisson_ratio * s / m.youngs_modulus};
  double sigma[9];
  stress<3>(m, grad, sigma);
  EXPECT_NEAR(sigma[0], s, 1e-12);
  EXPECT_NEAR(sigma[4], 0, 1e-12);
  EXPECT_NEAR(von_mises<3>(m, sigma), s, 1e-12);
  const double shear[9] = {0, 1.5, 0, 1.5, 0, 0, 0, 0, 0};
  EXPECT_NEAR(von_mises<3>(m, shear), std::sqrt(3.0) * 1.5, 1e-12);
  ElasticityProblem<2> bad;
  bad.material.poisson_ratio = 0.5;
  auto solver = make_solver("cholmod");
  EXPECT_THROW(solve_elasticity(TensorSpace<2>{iga_test::distorted_box<2>(1, 1, false, 1)}, bad, *solver), Error);
}
