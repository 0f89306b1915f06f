#include "trivar/iga/lr_solution_field.hpp"

#include <random>

#include <gtest/gtest.h>

#include "iga/iga_test_support.hpp"
#include "trivar/core/error.hpp"
#include "trivar/iga/refined_space.hpp"

using namespace trivar;

namespace {

// The field at u equals sum_l c_l R_l(u) over the analysis basis of the element containing u.
template <int D>
void expect_field_is_the_expansion(const LRSpline<D>& g, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> coef(-1, 1), param(0, 1);
  Eigen::VectorXd c(g.num_basis());
  for (int i = 0; i < g.num_basis(); ++i) c[i] = coef(rng);
  const LRSpline<D> field = lr_solution_field(g, c);
  EXPECT_EQ(field.dim(), 1);
  EXPECT_EQ(field.num_basis(), g.num_basis());
  const auto space = refined_space(g);
  RefinedPoint<D> p;
  for (int q = 0; q < 50; ++q) {
    Param<D> u;
    for (int k = 0; k < D; ++k) u[k] = g.domain().lo[k] + g.domain().extent(k) * param(rng);
    const auto& el = space.elements[static_cast<std::size_t>(space.locate(u))];
    refined_point(space, el, u, p);
    double expected = 0;
    for (std::size_t l = 0; l < el.ids.size(); ++l) expected += c[el.ids[l]] * p.R[l];
    double value;
    field.eval(u, &value);
    EXPECT_NEAR(value, expected, 1e-13) << D << " " << q;
  }
}

}  // namespace

TEST(LRSolutionField, IsTheExpansionInTheAnalysisBasis) {
  LRSpline<2> s(iga_test::distorted_box<2>(2, 4, false, 1));
  iga_test::refine_corner(s, 0.5);
  iga_test::refine_corner(s, 0.25);
  ASSERT_TRUE(iga_test::has_t_junction(s));
  expect_field_is_the_expansion<2>(s, 2);
  LRSpline<3> v(iga_test::distorted_box<3>(2, 4, false, 3));
  iga_test::refine_corner(v, 0.25);
  ASSERT_TRUE(iga_test::has_t_junction(v));
  expect_field_is_the_expansion<3>(v, 4);
  EXPECT_THROW(lr_solution_field(s, Eigen::VectorXd::Zero(3)), Error);
}
