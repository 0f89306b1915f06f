#include "trivar/iga/poisson.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "trivar/iga/error_norms.hpp"

using namespace trivar;

namespace {

constexpr double pi = std::numbers::pi;

// u = sin(pi x) sin(pi y) on the unit square, -lap u = 2 pi^2 u.
PoissonProblem<2> sine_square() {
  PoissonProblem<2> p;
  p.source = [](const double* x) { return 2 * pi * pi * std::sin(pi * x[0]) * std::sin(pi * x[1]); };
  p.dirichlet.push_back({all_faces<2>(), {}, nullptr});
  return p;
}

void sine_square_exact(const double* x, double* u, double* g) {
  u[0] = std::sin(pi * x[0]) * std::sin(pi * x[1]);
  g[0] = pi * std::cos(pi * x[0]) * std::sin(pi * x[1]);
  g[1] = pi * std::sin(pi * x[0]) * std::cos(pi * x[1]);
}

}  // namespace

TEST(Poisson, SineSquareConvergesAtOptimalRates) {
  for (int p = 1; p <= 3; ++p) {
    ErrorNorms prev;
    for (int n : {4, 8, 16}) {
      const TensorSpace<2> space{box_geometry<2>({0, 0}, {1, 1}, p, n)};
      auto solver = make_solver("cholmod");
      const SolveResult r = solve_poisson(space, sine_square(), *solver);
      const ErrorNorms e = error_norms<2>(space, r.coefs, 1, sine_square_exact);
      if (n > 4) {
        EXPECT_NEAR(std::log2(prev.l2 / e.l2), p + 1, 0.25) << "p " << p << " n " << n;
        EXPECT_NEAR(std::log2(prev.h1 / e.h1), p, 0.25) << "p " << p << " n " << n;
      }
      prev = e;
    }
  }
}
