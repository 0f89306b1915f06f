// Linear elasticity on LR spaces: agreement with the tensor solve on unrefined spaces, the patch test on
// locally refined meshes, and a-priori convergence rates for a manufactured solution.
#include "trivar/iga/refined_elasticity.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "iga/iga_test_support.hpp"
#include "trivar/core/error.hpp"
#include "trivar/iga/refined_poisson.hpp"

using namespace trivar;
using iga_test::faces_on_side;

namespace {

// Displacement u = exact on `fixed`, traction sigma(u) n on `loaded`; the body force is the caller's.
template <int D>
ElasticityProblem<D> mixed_problem(const ElasticMaterial& m, const ExactSolution<D>& exact, std::vector<Face> fixed,
                                   std::vector<Face> loaded) {
  ElasticityProblem<D> p;
  p.material = m;
  p.displacement.push_back({std::move(fixed), {}, [exact](const double* x, double* u) {
                              double g[D * D];
                              exact(x, u, g);
                            }});
  p.traction_faces = std::move(loaded);
  p.traction = [m, exact](const double* x, const double* n, double* t) {
    double u[D], g[D * D], s[D * D];
    exact(x, u, g);
    stress<D>(m, g, s);
    for (int i = 0; i < D; ++i) {
      t[i] = 0;
      for (int j = 0; j < D; ++j) t[i] += s[i * D + j] * n[j];
    }
  };
  return p;
}

// u_c = sin(x_c + c) cos(x_(c+1)): any smooth data serves to compare two solvers.
template <int D>
void smooth_field(const double* x, double* u, double* g) {
  for (int c = 0; c < D; ++c) {
    const int n = (c + 1) % D;
    u[c] = std::sin(x[c] + c) * std::cos(x[n]);
    for (int k = 0; k < D; ++k) g[c * D + k] = 0;
    g[c * D + c] = std::cos(x[c] + c) * std::cos(x[n]);
    g[c * D + n] = -std::sin(x[c] + c) * std::sin(x[n]);
  }
}

template <int D>
void expect_same_as_tensor(unsigned seed) {
  const TensorSpace<D> space{iga_test::distorted_box<D>(2, 3, false, seed)};
  ElasticityProblem<D> p = mixed_problem<D>({200.0, 0.3}, smooth_field<D>, faces_on_side<D>(0), faces_on_side<D>(1));
  // A graded material: both solvers must ask material_at at the same points.
  p.material_at = [](int, const double* x) { return ElasticMaterial{100.0 + 50 * x[0], 0.25}; };
  p.body_force = [](const double* x, double* f) {
    for (int c = 0; c < D; ++c) f[c] = std::cos(x[c]) + c;
  };
  // One component of an end face held as well: the per-component projection next to a traction.
  p.displacement.push_back({{{1, 1}}, {D - 1}, [](const double* x, double* u) { u[D - 1] = 0.01 * x[0]; }});
  auto solver = make_solver("cholmod");
  const SolveResult tr = solve_elasticity(space, p, *solver);
  const LRSpline<D> lr(space.geometry);
  const SolveResult r = solve_elasticity(refined_space(lr), p, *solver);
  EXPECT_EQ(r.dofs, tr.dofs);
  ASSERT_EQ(r.coefs.size(), tr.coefs.size());
  // A converted tensor spline keeps its basis order, so the coefficient vectors compare entry by entry.
  EXPECT_LE((r.coefs - tr.coefs).lpNorm<Eigen::Infinity>(), 1e-10 * tr.coefs.lpNorm<Eigen::Infinity>()) << D;
}

// u = G x + a: constant stress, no body force.
template <int D>
void linear_field(const double* x, double* u, double* g) {
  for (int i = 0; i < D; ++i) {
    u[i] = 0.1 * (i + 1);
    for (int j = 0; j < D; ++j) {
      const double Gij = 0.01 * (1 + i - 2 * j) + (i == j ? 0.02 : 0.0);
      u[i] += Gij * x[j];
      g[i * D + j] = Gij;
    }
  }
}

template <int D>
void expect_patch_test(const LRSpline<D>& lr) {
  const ElasticityProblem<D> p =
      mixed_problem<D>({200.0, 0.25}, linear_field<D>, faces_on_side<D>(0), faces_on_side<D>(1));
  iga_test::expect_reproduced<D>(lr, D, linear_field<D>,
                                 [&](const RefinedSpace<D>& space, LinearSolver& s) {
                                   return solve_elasticity(space, p, s);
                                 });
}

}  // namespace

TEST(LRElasticity, PatchTestOnLocallyRefinedMeshes) {
  // A linear displacement has constant stress, so with its displacement on the start faces and its traction on
  // the end faces it is the Galerkin solution in any space that holds it: the isoparametric space does on a
  // curved polynomial map. The rules are exact for the terms that matter (sigma : int grad v and the traction
  // integrals have polynomial integrands: cofactor(J) times dR), as long as the cofactors stay of low degree:
  // p = 2 in 2-D, p = 1 in 3-D (see the LR Neumann test).
  LRSpline<2> square(iga_test::distorted_box<2>(2, 4, false, 21));
  iga_test::refine_corner(square, 0.5);
  iga_test::refine_corner(square, 0.25);
  expect_patch_test<2>(square);
  LRSpline<3> cube(iga_test::distorted_box<3>(1, 4, false, 22));
  iga_test::refine_corner(cube, 0.5);
  expect_patch_test<3>(cube);
}

TEST(LRElasticity, UnrefinedSpaceGivesTheTensorSolution) {
  expect_same_as_tensor<2>(7);
  expect_same_as_tensor<3>(8);
}

TEST(LRElasticity, InvalidMaterialThrowsAfterAssembly) {
  ElasticityProblem<2> bad;
  bad.material.poisson_ratio = 0.5;
  bad.displacement.push_back({{{0, 0}}, {}, nullptr});
  const LRSpline<2> lr(box_geometry<2>({0, 0}, {1, 1}, 2, 2));
  auto solver = make_solver("cholmod");
  EXPECT_THROW(solve_elasticity(refined_space(lr), bad, *solver), Error);
}

TEST(LRElasticity, ConvergesAtOptimalRatesOnLocallyRefinedSpaces) {
  // u = (sin(2x + 1) cos(3y), cos(x) sin(2y + 1/2)) through one fixed curved polynomial map (plane strain),
  // f = -div sigma(u) = -(mu lap u + (lambda + mu) grad div u) from Navier's equation by hand:
  // lap u = (-13 u_1, -5 u_2), grad div u = (-4 u_1 - 2 sin x cos(2y + 1/2), -6 cos(2x + 1) sin 3y - 4 u_2).
  // Displacement on x = 0 and y = 0, traction on x = 1 and y = 1. Each space: n elements per direction, then
  // the elements in [0, 1/4]^2 refined once more; the largest elements keep h = 1/n, so a-priori theory gives
  // L2 ~ h^(p+1), H1 ~ h^p.
  const ElasticMaterial m{200.0, 0.3};
  const ExactSolution<2> exact = [](const double* x, double* u, double* g) {
    u[0] = std::sin(2 * x[0] + 1) * std::cos(3 * x[1]);
    u[1] = std::cos(x[0]) * std::sin(2 * x[1] + 0.5);
    g[0] = 2 * std::cos(2 * x[0] + 1) * std::cos(3 * x[1]);
    g[1] = -3 * std::sin(2 * x[0] + 1) * std::sin(3 * x[1]);
    g[2] = -std::sin(x[0]) * std::sin(2 * x[1] + 0.5);
    g[3] = 2 * std::cos(x[0]) * std::cos(2 * x[1] + 0.5);
  };
  ElasticityProblem<2> p = mixed_problem<2>(m, exact, {{0, 0}, {1, 0}}, {{0, 1}, {1, 1}});
  p.body_force = [m](const double* x, double* f) {
    const double lambda = m.lambda(), mu = m.mu();
    const double u1 = std::sin(2 * x[0] + 1) * std::cos(3 * x[1]), u2 = std::cos(x[0]) * std::sin(2 * x[1] + 0.5);
    f[0] = 13 * mu * u1 + (lambda + mu) * (4 * u1 + 2 * std::sin(x[0]) * std::cos(2 * x[1] + 0.5));
    f[1] = 5 * mu * u2 + (lambda + mu) * (6 * std::cos(2 * x[0] + 1) * std::sin(3 * x[1]) + 4 * u2);
  };
  const TensorSpline<2> map = iga_test::distorted_box<2>(2, 2, false, 5);
  const std::vector<ErrorNorms> e = iga_test::expect_optimal_convergence<2>(
      map, 2, 2, exact, [&](const RefinedSpace<2>& space, LinearSolver& s) {
        return solve_elasticity(space, p, s);
      });
  for (std::size_t i = 0; i < e.size(); ++i) {
    std::ostringstream errors;
    errors << std::scientific << std::setprecision(4) << e[i].l2 << " " << e[i].h1;
    RecordProperty("l2_h1_n" + std::to_string(4 << i), errors.str());
  }
}
