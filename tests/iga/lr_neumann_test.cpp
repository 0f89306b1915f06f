// Neumann data on LR spaces: the boundary load of solve_poisson and the Neumann term of the residual indicator.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "iga/iga_test_support.hpp"
#include "trivar/iga/error_indicator.hpp"
#include "trivar/iga/refined_poisson.hpp"

using namespace trivar;
using iga_test::faces_on_side;

namespace {

// Dirichlet data u = exact on `dirichlet`, Neumann data g = grad u . n on `neumann`, f = -lap u.
template <int D>
PoissonProblem<D> mixed_problem(const ExactSolution<D>& exact, std::function<double(const double*)> source,
                                std::vector<Face> dirichlet, std::vector<Face> neumann) {
  PoissonProblem<D> p;
  p.source = std::move(source);
  p.dirichlet.push_back({std::move(dirichlet), {}, [exact](const double* x, double* u) {
                           double g[D];
                           exact(x, u, g);
                         }});
  p.neumann = std::move(neumann);
  p.flux = [exact](const double* x, const double* n) {
    double u, g[D], s = 0;
    exact(x, &u, g);
    for (int k = 0; k < D; ++k) s += g[k] * n[k];
    return s;
  };
  return p;
}

// exp(x) sin(y) is harmonic; in 3-D u gets + z^2, so f = -lap u = -2.
template <int D>
void smooth_exact(const double* x, double* u, double* g) {
  u[0] = std::exp(x[0]) * std::sin(x[1]);
  g[0] = u[0];
  g[1] = std::exp(x[0]) * std::cos(x[1]);
  if constexpr (D == 3) {
    u[0] += x[2] * x[2];
    g[2] = 2 * x[2];
  }
}

template <int D>
void expect_same_as_tensor(int seed) {
  const TensorSpace<D> space{iga_test::distorted_box<D>(2, 3, false, static_cast<unsigned>(seed))};
  // Dirichlet on the start faces, Neumann on the end faces.
  const PoissonProblem<D> p = mixed_problem<D>(
      smooth_exact<D>, [](const double*) { return D == 3 ? -2.0 : 0.0; }, faces_on_side<D>(0), faces_on_side<D>(1));
  auto solver = make_solver("cholmod");
  const SolveResult tr = solve_poisson(space, p, *solver);
  const LRSpline<D> lr(space.geometry);
  const SolveResult r = solve_poisson(refined_space(lr), p, *solver);
  EXPECT_EQ(r.dofs, tr.dofs);
  ASSERT_EQ(r.coefs.size(), tr.coefs.size());
  // A converted tensor spline keeps its basis order, so the coefficient vectors compare entry by entry.
  EXPECT_LE((r.coefs - tr.coefs).lpNorm<Eigen::Infinity>(), 1e-10 * tr.coefs.lpNorm<Eigen::Infinity>()) << D;
}

// Solves p on a space: the solver that iga_test::expect_reproduced checks.
template <int D>
auto poisson_on(const PoissonProblem<D>& p) {
  return [&p](const RefinedSpace<D>& space, LinearSolver& s) { return solve_poisson(space, p, s); };
}

}  // namespace

TEST(LRNeumann, UnrefinedSpaceGivesTheTensorSolution) {
  expect_same_as_tensor<2>(3);
  expect_same_as_tensor<3>(4);
}

TEST(LRNeumann, ReproducesPolynomialsInTheSpaceOnLocallyRefinedMeshes) {
  // u = x^2 y^2 - 2 x y + 3 x - y is biquadratic: on the identity map with p = 2 it lies in every LR space, so
  // with f = -lap u and exact Dirichlet and Neumann data the Galerkin solution is u up to rounding (all
  // integrands are polynomials integrated exactly by the p + 1 / p + 2 point rules).
  {
    const ExactSolution<2> exact = [](const double* x, double* u, double* g) {
      u[0] = x[0] * x[0] * x[1] * x[1] - 2 * x[0] * x[1] + 3 * x[0] - x[1];
      g[0] = 2 * x[0] * x[1] * x[1] - 2 * x[1] + 3;
      g[1] = 2 * x[0] * x[0] * x[1] - 2 * x[0] - 1;
    };
    const PoissonProblem<2> p = mixed_problem<2>(
        exact, [](const double* x) { return -2 * (x[0] * x[0] + x[1] * x[1]); }, {{1, 0}}, {{0, 0}, {0, 1}, {1, 1}});
    LRSpline<2> lr(box_geometry<2>({0, 0}, {1, 1}, 2, 4));
    iga_test::refine_corner(lr, 0.5);
    iga_test::refine_corner(lr, 0.25);
    iga_test::expect_reproduced<2>(lr, 1, exact, poisson_on(p));
  }
  // Linear u on a curved polynomial map (p = 1 in 3-D: the isoparametric space holds x, y, z, and with k = 1
  // the stiffness and face integrands stay within the exact degree of the rules, see the tensor patch test).
  {
    const ExactSolution<3> exact = [](const double* x, double* u, double* g) {
      u[0] = 1 + 2 * x[0] - 3 * x[1] + 0.5 * x[2];
      g[0] = 2;
      g[1] = -3;
      g[2] = 0.5;
    };
    const PoissonProblem<3> p = mixed_problem<3>(exact, nullptr, faces_on_side<3>(0), faces_on_side<3>(1));
    LRSpline<3> lr(iga_test::distorted_box<3>(1, 4, false, 11));
    iga_test::refine_corner(lr, 0.5);
    iga_test::expect_reproduced<3>(lr, 1, exact, poisson_on(p));
  }
}

TEST(LRNeumann, ConvergesAtOptimalRatesOnLocallyRefinedSpaces) {
  // u = sin(2x + 1) cos(3y), -lap u = 13 u, on the unit square through one fixed curved polynomial map,
  // Dirichlet on x = 0 and y = 0, Neumann on x = 1 and y = 1. Each space: n elements per direction, then the
  // elements in [0, 1/4]^2 refined once more. The largest elements keep h = 1/n, so a-priori theory gives
  // L2 ~ h^(p+1), H1 ~ h^p.
  const ExactSolution<2> exact = [](const double* x, double* u, double* g) {
    u[0] = std::sin(2 * x[0] + 1) * std::cos(3 * x[1]);
    g[0] = 2 * std::cos(2 * x[0] + 1) * std::cos(3 * x[1]);
    g[1] = -3 * std::sin(2 * x[0] + 1) * std::sin(3 * x[1]);
  };
  const PoissonProblem<2> p = mixed_problem<2>(
      exact,
      [exact](const double* x) {
        double u, g[2];
        exact(x, &u, g);
        return 13 * u;
      },
      {{0, 0}, {1, 0}}, {{0, 1}, {1, 1}});
  const TensorSpline<2> map = iga_test::distorted_box<2>(2, 2, false, 5);
  for (int deg : {2, 3})
    iga_test::expect_optimal_convergence<2>(map, deg, 1, exact,
                                            [&](const RefinedSpace<2>& space, LinearSolver& s) {
                                              return solve_poisson(space, p, s);
                                            });
}

namespace {

// u_h = x (the identity map's own x coefficients) on the unit box with f = 0: no interior residual and no
// jumps, so the indicator is the Neumann term alone. Dirichlet on y = 0 (ignored), Neumann g = 3 on x = 1
// (mismatch 3 - 1 = 2), and x = 0 natural (g = 0, du_h/dn = -1: mismatch 1); the other faces have
// du_h/dn = 0. So eta_K^2 = h_K (4 |S_1| + |S_0|) with S_0, S_1 the sides of K on x = 0, x = 1 and
// h_K = |K|^(1/D), on any mesh. Returns the sum of eta_K^2.
template <int D>
double expect_neumann_indicator(const LRSpline<D>& lr) {
  PoissonProblem<D> p;
  p.dirichlet.push_back({{{1, 0}}, {}, nullptr});
  p.neumann = {{0, 1}};
  p.flux = [](const double*, const double*) { return 3.0; };
  Eigen::VectorXd x(lr.num_basis());
  for (int i = 0; i < lr.num_basis(); ++i) x[i] = lr.basis_function(i).coef[0];
  const auto eta = residual_indicators(refined_space(lr), p, x);
  EXPECT_EQ(static_cast<int>(eta.size()), lr.num_elements());
  double total = 0, expected_total = 0;
  for (int e = 0; e < lr.num_elements(); ++e) {
    const Box<D>& b = lr.element(e);
    double volume = 1, side = 1;
    for (int k = 0; k < D; ++k) {
      volume *= b.extent(k);
      if (k != 0) side *= b.extent(k);
    }
    const double weight = 4.0 * (b.hi[0] == 1.0) + 1.0 * (b.lo[0] == 0.0);
    const double expected = std::pow(volume, 1.0 / D) * weight * side;
    EXPECT_NEAR(eta[static_cast<std::size_t>(e)] * eta[static_cast<std::size_t>(e)], expected, 1e-12) << D << " " << e;
    total += eta[static_cast<std::size_t>(e)] * eta[static_cast<std::size_t>(e)];
    expected_total += expected;
  }
  EXPECT_NEAR(total, expected_total, 1e-12);
  return total;
}

}  // namespace

TEST(ResidualIndicator, NeumannSidesCarryTheFluxMismatch) {
  // Uniform n x n mesh: eta^2 = n (1/n) (4 + 1) (1/n) = 5/n.
  LRSpline<2> square(box_geometry<2>({0, 0}, {1, 1}, 2, 4));
  EXPECT_NEAR(expect_neumann_indicator<2>(square), 5.0 / 4, 1e-12);
  // Locally refined meshes in 2-D and 3-D.
  iga_test::refine_corner(square, 0.25);
  ASSERT_TRUE(iga_test::has_t_junction(square));
  expect_neumann_indicator<2>(square);
  LRSpline<3> cube(box_geometry<3>({0, 0, 0}, {1, 1, 1}, 2, 4));
  iga_test::refine_corner(cube, 0.25);
  ASSERT_TRUE(iga_test::has_t_junction(cube));
  expect_neumann_indicator<3>(cube);
}
