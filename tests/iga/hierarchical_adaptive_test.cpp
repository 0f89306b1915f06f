// Adaptive Poisson on hierarchical spaces (HB, THB) through the common locally refined space: the unrefined
// space reproduces the tensor solution, refined spaces reproduce polynomials of the space, and the adaptive
// L-shape loop reaches the optimal rate in dofs (H1 error ~ N^(-p/2) in 2-D for the r^(2/3) singularity, which
// uniform refinement limits to N^(-1/3)).
#include <cmath>

#include <gtest/gtest.h>

#include "hier/hier_test_support.hpp"
#include "iga/iga_test_support.hpp"
#include "trivar/iga/adaptive_loop.hpp"
#include "trivar/iga/benchmark_problems.hpp"
#include "trivar/iga/refined_assembly.hpp"
#include "trivar/iga/refined_poisson.hpp"
#include "trivar/iga/refined_space.hpp"

using namespace trivar;

namespace {

// Least-squares slope of log(H1 error) against log(dofs) over the rows from `first` on.
double h1_rate(const std::vector<ConvergenceRow>& rows, std::size_t first) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(rows.size() - first);
  for (std::size_t i = first; i < rows.size(); ++i) {
    const double x = std::log(rows[i].dofs), y = std::log(rows[i].h1);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return -(n * sxy - sx * sy) / (n * sxx - sx * sx);
}

}  // namespace

TEST(HierarchicalPoisson, UnrefinedSpaceGivesTheTensorSolution) {
  const PoissonBenchmark<2> b = sine_box<2>(2, 6);
  auto solver = make_solver("cholmod");
  const SolveResult tr = solve_poisson(b.space, b.problem, *solver);
  for (auto basis : {HierarchicalBasis::hb, HierarchicalBasis::thb}) {
    const HierarchicalSpline<2> h(b.space.geometry, basis);
    const SolveResult r = solve_poisson(refined_space(h), b.problem, *solver);
    ASSERT_EQ(r.coefs.size(), tr.coefs.size());
    EXPECT_LE((r.coefs - tr.coefs).lpNorm<Eigen::Infinity>(), 1e-10 * tr.coefs.lpNorm<Eigen::Infinity>());
  }
}

TEST(HierarchicalPoisson, HBAndTHBGiveTheSameSolutionOnRefinedSpaces) {
  // The bases span the same space: the discrete solutions coincide (same errors), the THB matrix is sparser.
  const PoissonBenchmark<2> b = l_shape(2, 4);
  HierarchicalSpline<2> h(b.space.geometry, HierarchicalBasis::thb);
  for (int l = 0; l < 4; ++l) {
    std::vector<int> corner;
    for (int e = 0; e < h.space().num_elements(); ++e) {
      const Box<2> box = h.space().element_box(e);
      if (box.lo[0] < 0.6 && box.hi[0] > 0.4) corner.push_back(e);  // a band across the re-entrant corner
    }
    h.refine_elements(corner);
  }
  auto solver = make_solver("cholmod");
  const auto thb = refined_space(h);
  const HierarchicalSpline<2> hbs = h.with_basis(HierarchicalBasis::hb);
  const auto hb = refined_space(hbs);
  const SolveResult rt = solve_poisson(thb, b.problem, *solver), rh = solve_poisson(hb, b.problem, *solver);
  const ErrorNorms et = error_norms(thb, rt.coefs, 1, b.exact), eh = error_norms(hb, rh.coefs, 1, b.exact);
  EXPECT_NEAR(et.h1, eh.h1, 1e-9 * eh.h1);
  EXPECT_NEAR(et.l2, eh.l2, 1e-9 * eh.l2);
  // Truncation shrinks supports: fewer stiffness entries than HB.
  auto nnz = [](const RefinedSpace<2>& s) {
    return assemble_refined_system<2>(
               s, 1, 0,
               [](const RefinedPoint<2>& p, const std::vector<double>& grad, double dV, Eigen::MatrixXd& K, Eigen::VectorXd&) {
                 const Eigen::Index m = static_cast<Eigen::Index>(p.R.size());
                 const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>> G(grad.data(), m, 2);
                 K.noalias() += dV * G * G.transpose();
               },
               [](const RefinedElement<2>&, Eigen::VectorXd&) {})
        .A.nonZeros();
  };
  EXPECT_LT(nnz(thb), nnz(hb));
}

// The admissible loop (class 2) keeps its bound on every mesh it makes and still converges at the optimal rate.
TEST(HierarchicalPoisson, AdmissibleAdaptiveLShape) {
  const PoissonBenchmark<2> b = l_shape(2, 4);
  HierarchicalSpline<2> h(b.space.geometry, HierarchicalBasis::thb);
  AdaptiveOptions o;
  o.steps = 12;
  o.admissible = 2;
  const auto rows = adaptive_poisson(h, b.problem, b.exact, o);
  EXPECT_GE(h1_rate(rows, rows.size() / 2), 1.0 - 0.1);
  const auto [levels, functions] = test::levels_and_functions_per_element(h.space());
  EXPECT_LE(levels, 2);
  EXPECT_LE(functions, 2 * 9);
}

TEST(HierarchicalPoisson, AdaptiveLShapeReachesTheOptimalRate) {
  for (int p : {2, 3}) {
    const PoissonBenchmark<2> b = l_shape(p, 4);
    HierarchicalSpline<2> h(b.space.geometry, HierarchicalBasis::thb);
    AdaptiveOptions o;
    o.steps = p == 2 ? 22 : 18;
    o.beta = 0.3;
    const auto rows = adaptive_poisson(h, b.problem, b.exact, o);
    ASSERT_EQ(rows.size(), static_cast<std::size_t>(o.steps));
    for (std::size_t i = 1; i < rows.size(); ++i) EXPECT_GT(rows[i].dofs, rows[i - 1].dofs);
    iga_test::expect_efficient_estimates(rows);
    // Optimal: p / 2. Uniform refinement gives 1/3 whatever p.
    const double rate = h1_rate(rows, rows.size() / 2);
    EXPECT_GE(rate, 0.5 * p - 0.1) << "p = " << p;
    EXPECT_GT(h.space().num_levels(), 8);
  }
}
