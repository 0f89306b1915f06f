#include "trivar/iga/poisson.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "iga/iga_test_support.hpp"
#include "trivar/core/error.hpp"
#include "trivar/iga/benchmark_problems.hpp"
#include "trivar/iga/error_norms.hpp"

using namespace trivar;

namespace {

template <int D>
ErrorNorms solve_and_measure(const PoissonBenchmark<D>& b, const std::string& solver_name = "cholmod") {
  auto solver = make_solver(solver_name);
  const SolveResult r = solve_poisson(b.space, b.problem, *solver);
  return error_norms<D>(b.space, r.coefs, 1, b.exact);
}

// Observed rates r = log2(e(h) / e(h/2)) against the a-priori orders p + 1 (L2) and p (H1): on coarse
// meshes the error may still fall faster than asymptotically (r above the order, by at most `above`), never
// slower (r >= order - 0.15); the last pair must be within `last` of the order.
void expect_rate(double r, int order, bool last, double above, double last_tol, const std::string& what) {
  EXPECT_GE(r, order - 0.15) << what;
  EXPECT_LE(r, order + above) << what;
  if (last) {
    EXPECT_NEAR(r, order, last_tol) << what;
  }
}

template <int D>
void expect_optimal_rates(int p, const std::vector<int>& sizes, double last_tol) {
  ErrorNorms prev;
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    const ErrorNorms e = solve_and_measure(sine_box<D>(p, sizes[i]));
    if (i > 0) {
      const bool last = i + 1 == sizes.size();
      const std::string what = "p " + std::to_string(p) + " n " + std::to_string(sizes[i]);
      expect_rate(std::log2(prev.l2 / e.l2), p + 1, last, 0.6, last_tol, what + " L2");
      expect_rate(std::log2(prev.h1 / e.h1), p, last, 0.6, last_tol, what + " H1");
    }
    prev = e;
  }
}

}  // namespace

TEST(Poisson, SineSquareConvergesAtOptimalRates) {
  for (int p = 1; p <= 4; ++p) expect_optimal_rates<2>(p, {4, 8, 16, 32}, 0.15);
}

TEST(Poisson, SineCubeConvergesAtOptimalRates) {
  expect_optimal_rates<3>(2, {4, 8}, 0.45);
  expect_optimal_rates<3>(3, {4, 8}, 0.45);
}

TEST(Poisson, PatchTestReproducesLinearSolutionOnCurvedNurbs) {
  // u = 1 + 2x - 3y (+ 0.5z) lies in every space whose geometry map does (x = sum x_I R_I), so the projected
  // Dirichlet data and the Galerkin solution are exact up to rounding, whatever the distortion, as long as
  // quadrature is exact. On a polynomial map the integrand k grad u . cof(J) grad_u R_I has degree per
  // direction <= (D - 1) p + p (+ p for k = 1 + x), and p + 1 Gauss points integrate degree 2p + 1: so
  // p = 2 with variable k in 2-D, p = 1 with k = 1 in 3-D. (NURBS maps give rational integrands; there the
  // test holds only up to quadrature error.)
  // Dirichlet on the start faces, Neumann k du/dn = k grad u . n on the end faces.
  auto run = [](auto dim_tag, int degree, bool variable_k) {
    constexpr int D = decltype(dim_tag)::value;
    const double c[3] = {2, -3, 0.5};
    auto exact = [c](const double* x, double* u, double* g) {
      u[0] = 1;
      for (int k = 0; k < D; ++k) {
        u[0] += c[k] * x[k];
        g[k] = c[k];
      }
    };
    PoissonProblem<D> p;
    auto conductivity = [variable_k](const double* x) { return variable_k ? 1 + x[0] : 1.0; };
    p.conductivity = conductivity;
    // -div((1 + x) grad u) = -c_0.
    if (variable_k) p.source = [c](const double*) { return -c[0]; };
    std::vector<Face> starts, ends;
    for (int k = 0; k < D; ++k) {
      starts.push_back({k, 0});
      ends.push_back({k, 1});
    }
    p.dirichlet.push_back({starts, {}, [exact](const double* x, double* u) {
                             double g[3];
                             exact(x, u, g);
                           }});
    p.neumann = ends;
    p.flux = [c, conductivity](const double* x, const double* n) {
      double s = 0;
      for (int a = 0; a < D; ++a) s += c[a] * n[a];
      return conductivity(x) * s;
    };
    const TensorSpace<D> space{iga_test::distorted_box<D>(degree, 3, false, 21)};
    auto solver = make_solver("cholmod");
    const SolveResult r = solve_poisson(space, p, *solver);
    const ErrorNorms e = error_norms<D>(space, r.coefs, 1, exact);
    EXPECT_LE(e.l2, 1e-10) << D;
    EXPECT_LE(e.h1, 1e-10) << D;
  };
  run(std::integral_constant<int, 2>{}, 2, true);
  run(std::integral_constant<int, 3>{}, 1, false);
}

TEST(Poisson, CurvedDomainWithDirichletAndNeumannData) {
  // Harmonic u = exp(x) sin(y) on the quarter annulus 1 <= r <= 2 (exact rational geometry): Dirichlet data on
  // the two arcs, Neumann data on the two straight sides. Rates p + 1 and p on the NURBS space.
  auto exact = [](const double* x, double* u, double* g) {
    u[0] = std::exp(x[0]) * std::sin(x[1]);
    g[0] = u[0];
    g[1] = std::exp(x[0]) * std::cos(x[1]);
  };
  PoissonProblem<2> p;
  p.dirichlet.push_back({{{0, 0}, {0, 1}}, {}, [exact](const double* x, double* u) {
                           double g[2];
                           exact(x, u, g);
                         }});
  p.neumann = {{1, 0}, {1, 1}};
  p.flux = [exact](const double* x, const double* n) {
    double u, g[2];
    exact(x, &u, g);
    return g[0] * n[0] + g[1] * n[1];
  };
  for (int deg : {2, 3}) {
    ErrorNorms prev;
    for (int n : {4, 8, 16, 32}) {
      const TensorSpace<2> space = make_tensor_space(quarter_annulus<2>(1.0, 2.0), deg, n);
      auto solver = make_solver("cholmod");
      const SolveResult r = solve_poisson(space, p, *solver);
      const ErrorNorms e = error_norms<2>(space, r.coefs, 1, exact);
      if (n > 4) {
        const std::string what = "p " + std::to_string(deg) + " n " + std::to_string(n);
        expect_rate(std::log2(prev.l2 / e.l2), deg + 1, n == 32, 0.7, 0.2, what + " L2");
        expect_rate(std::log2(prev.h1 / e.h1), deg, n == 32, 0.7, 0.2, what + " H1");
      }
      prev = e;
    }
  }
}

TEST(Poisson, IterativeAndDirectSolversAgree) {
  const PoissonBenchmark<3> b = sine_box<3>(3, 4);
  Eigen::VectorXd ref;
  for (const char* name : {"cholmod", "cg", "cg-ichol"}) {
    auto solver = make_solver(name, 1e-12);
    const SolveResult r = solve_poisson(b.space, b.problem, *solver);
    if (ref.size() == 0)
      ref = r.coefs;
    else
      EXPECT_LE((r.coefs - ref).norm(), 1e-9 * ref.norm()) << name;
  }
  EXPECT_THROW(make_solver("petsc"), Error);
}

TEST(Poisson, RejectsBadInput) {
  EXPECT_THROW(sine_box<3>(0, 4), Error);
  EXPECT_THROW(sine_box<3>(2, 0), Error);
  EXPECT_THROW(make_tensor_space(quarter_annulus<2>(1.0, 2.0), 0, 2), Error);
  EXPECT_THROW(quarter_annulus<2>(2.0, 1.0), Error);
}
