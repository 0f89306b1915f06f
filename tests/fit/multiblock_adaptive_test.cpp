// Adaptive refinement of multi-block models with T-joints: the L-shaped domain [-1, 1]^2 minus [0, 1] x [-1, 0]
// as three quadrant blocks with non-matching interfaces (2, 3 and 4 elements per direction), u = r^(2/3)
// sin(2 theta / 3) (the re-entrant corner singularity, iga's l-shape benchmark). Checks that the indicator's jumps
// across interfaces are the one-domain indicator's where the spaces coincide, that every adapted model stays
// conforming (a quadratic is reproduced on it to rounding) and that the adaptive loop reaches the optimal rate
// dofs^(-p/2) in H1 where uniform refinement of the blocks stays at dofs^(-1/3).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "trivar/fit/multiblock_adaptive.hpp"
#include "trivar/iga/benchmark_problems.hpp"
#include "trivar/iga/error_indicator.hpp"
#include "trivar/iga/refined_poisson.hpp"
#include "trivar/iga/tensor_space.hpp"
#include "trivar/spline/knot_insertion.hpp"

namespace trivar {
namespace {

// The three quadrants of the L-shape, degree p, `scale` times (2, 3, 4) elements per direction.
std::vector<LRSpline<2>> l_shape_quadrants(int p, int scale = 1) {
  return {LRSpline<2>(box_geometry<2>({0, 0}, {1, 1}, p, 2 * scale)),
          LRSpline<2>(box_geometry<2>({-1, 0}, {0, 1}, p, 3 * scale)),
          LRSpline<2>(box_geometry<2>({-1, -1}, {0, 0}, p, 4 * scale))};
}

// The l-shape benchmark's problem (f = 0, exact Dirichlet data) on the blocks' boundary faces.
PoissonProblem<2> corner_problem(const MultiblockSpace<2>& m, const ExactSolution<2>& exact) {
  PoissonProblem<2> pb;
  pb.dirichlet.push_back({boundary_faces(m), {}, [exact](const double* x, double* u) {
                            double g[2];
                            exact(x, u, g);
                          }});
  return pb;
}

// The point of the domain at the centre of an element's box.
Param<2> element_centre(const RefinedSpace<2>& s, const RefinedElement<2>& el) {
  RefinedPoint<2> pt;
  refined_point(s, el, {(el.box.lo[0] + el.box.hi[0]) / 2, (el.box.lo[1] + el.box.hi[1]) / 2}, pt);
  return {pt.x[0], pt.x[1]};
}

// Rate of the H1 error in dofs between two rows: e ~ dofs^(-rate).
double dof_rate(const ConvergenceRow& a, const ConvergenceRow& b) {
  return std::log(a.h1 / b.h1) / std::log(static_cast<double>(b.dofs) / a.dofs);
}

// A square split at x = 1/2 into two blocks with matching meshes is the one-patch space with a C0 line there: the
// same solution, and the same indicators element by element (the jumps across the interface found through the
// neighbour block are the one-domain indicator's jumps across the C0 line).
TEST(MultiblockAdaptive, InterfaceJumpsAreTheOneDomainIndicator) {
  const int p = 2;
  const TensorSpline<2> whole = box_geometry<2>({0, 0}, {1, 1}, p, 4);
  LRSpline<2> one(whole);
  const MultiblockSpace<2> m = multiblock_space<2>({LRSpline<2>(box_geometry<2>({0, 0}, {0.5, 1}, p, 2)),
                                                    LRSpline<2>(box_geometry<2>({0.5, 0}, {1, 1}, p, 2))});
  // The patch with the C0 line: knot 0.5 raised to multiplicity p.
  const TensorSpline<2> c0 = insert_knot(whole, 0, 0.5, p - 1);
  const LRSpline<2> lr(c0);
  const RefinedSpace<2> single = refined_space(lr);
  ASSERT_EQ(single.num_basis, m.space.num_basis);
  PoissonProblem<2> a, b;
  a.source = b.source = [](const double* x) { return std::exp(x[0]) * (1 + x[1] * x[1]); };
  a.dirichlet.push_back({all_faces<2>(), {}, nullptr});
  b.dirichlet.push_back({boundary_faces(m), {}, nullptr});
  auto solver = make_solver("cholmod");
  const SolveResult ra = solve_poisson(single, a, *solver, 1), rb = solve_poisson(m.space, b, *solver, 1);
  const std::vector<double> ea = residual_indicators(single, a, ra.coefs, 1);
  const std::vector<double> eb = residual_indicators(m.space, b, rb.coefs, 1, multiblock_across(m));
  // Elements matched by their centres in the square (the one patch's parameters are x).
  ASSERT_EQ(ea.size(), eb.size());
  double total = 0;
  int interface_elements = 0;
  for (std::size_t e = 0; e < eb.size(); ++e) {
    const Param<2> x = element_centre(m.space, m.space.elements[e]);
    const int k = single.locate(x);
    EXPECT_NEAR(eb[e], ea[static_cast<std::size_t>(k)], 1e-9 * ea[static_cast<std::size_t>(k)]) << e;
    if (m.space.elements[e].interface_sides) ++interface_elements;
    total += eb[e] * eb[e];
  }
  EXPECT_EQ(interface_elements, 8);
  EXPECT_GT(total, 1e-8);
  EXPECT_THROW(residual_indicators(m.space, b, rb.coefs, 1), Error);  // a multi-block space needs its neighbours
}

// The adaptive loop on the three-block L-shape: every model stays conforming (it is built by matching, which
// throws otherwise, and a quadratic is solved exactly on the last one), the refinement concentrates at the
// re-entrant corner, and the H1 error falls like dofs^(-1) (optimal for p = 2) while uniform refinement of the
// blocks gives dofs^(-1/3).
TEST(MultiblockAdaptive, LShapeOfThreeBlocksReachesTheOptimalRate) {
  const int p = 2;
  const ExactSolution<2> exact = l_shape(p, 1).exact;
  MultiblockSpace<2> m = multiblock_space(l_shape_quadrants(p));
  AdaptiveOptions o;
  o.steps = 9;
  o.beta = 0.3;
  const PoissonProblem<2> pb = corner_problem(m, exact);
  const std::vector<ConvergenceRow> rows = adaptive_poisson(m, pb, exact, o);
  ASSERT_EQ(rows.size(), 9u);
  for (std::size_t i = 1; i < rows.size(); ++i) {
    EXPECT_GT(rows[i].dofs, rows[i - 1].dofs);
    EXPECT_LT(rows[i].h1, rows[i - 1].h1);
  }
  for (const ConvergenceRow& r : rows) {
    EXPECT_GT(r.estimate / r.h1, 0.2);
    EXPECT_LT(r.estimate / r.h1, 20.0);
  }
  const double adaptive_rate = dof_rate(rows[rows.size() - 4], rows.back());
  EXPECT_GT(adaptive_rate, 0.8);

  // Refined towards the corner: the smallest element lies at the origin (every block's parameter box has the size
  // of its quadrant, so parameter areas are areas), and most elements lie near it.
  const auto smallest = std::min_element(m.space.elements.begin(), m.space.elements.end(), [](const auto& a, const auto& b) {
    return a.box.extent(0) * a.box.extent(1) < b.box.extent(0) * b.box.extent(1);
  });
  const Param<2> c = element_centre(m.space, *smallest);
  EXPECT_LT(std::hypot(c[0], c[1]), 0.05);
  const auto near = std::count_if(m.space.elements.begin(), m.space.elements.end(), [&](const RefinedElement<2>& el) {
    const Param<2> x = element_centre(m.space, el);
    return std::hypot(x[0], x[1]) < 0.25;
  });
  std::printf("near %ld of %d\n", static_cast<long>(near), m.space.num_elements());
  EXPECT_GT(2 * near, m.space.num_elements());

  // Conforming after the last step: u = x^2 - 3 x y + y^2 / 2 + x (lap u = 3) is reproduced to rounding.
  PoissonProblem<2> quadratic;
  quadratic.source = [](const double*) { return -3.0; };
  quadratic.dirichlet.push_back({boundary_faces(m), {}, [](const double* x, double* v) {
                                   v[0] = x[0] * x[0] - 3 * x[0] * x[1] + x[1] * x[1] / 2 + x[0];
                                 }});
  auto solver = make_solver("cholmod");
  const SolveResult q = solve_poisson(m.space, quadratic, *solver, 1);
  const ErrorNorms qe = error_norms(m.space, q.coefs, 1, [](const double* x, double* v, double* g) {
    v[0] = x[0] * x[0] - 3 * x[0] * x[1] + x[1] * x[1] / 2 + x[0];
    g[0] = 2 * x[0] - 3 * x[1] + 1;
    g[1] = -3 * x[0] + x[1];
  });
  EXPECT_LT(qe.h1, 1e-9);

  // Uniform refinement of the same blocks: rate about 1/3 in dofs, and more dofs for a larger error.
  std::vector<ConvergenceRow> uniform;
  for (int scale : {1, 2, 4}) {
    const MultiblockSpace<2> u = multiblock_space(l_shape_quadrants(p, scale));
    const SolveResult r = solve_poisson(u.space, corner_problem(u, exact), *solver, 1);
    ConvergenceRow row;
    row.dofs = r.dofs;
    row.h1 = error_norms(u.space, r.coefs, 1, exact, 1).h1;
    uniform.push_back(row);
  }
  EXPECT_NEAR(dof_rate(uniform[1], uniform[2]), 1.0 / 3.0, 0.08);
  EXPECT_GT(uniform.back().dofs, rows.back().dofs);
  EXPECT_GT(uniform.back().h1, rows.back().h1);
  for (const ConvergenceRow& r : rows) std::printf("adaptive dofs %d elements %d H1 %.3e estimate %.3e\n", r.dofs, r.elements, r.h1, r.estimate);
  for (const ConvergenceRow& r : uniform) std::printf("uniform dofs %d H1 %.3e\n", r.dofs, r.h1);
  std::printf("rates: adaptive %.3f, uniform %.3f\n", adaptive_rate, dof_rate(uniform[1], uniform[2]));
}

}  // namespace
}  // namespace trivar
