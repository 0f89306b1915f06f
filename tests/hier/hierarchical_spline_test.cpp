#include "trivar/hier/hierarchical_spline.hpp"

#include <gtest/gtest.h>

#include "hier/hier_test_support.hpp"
#include "trivar/core/error.hpp"
#include "trivar/spline/derivative_index.hpp"

using namespace trivar;
using namespace trivar::test;

namespace {

template <int D>
double max_difference(const TensorSpline<D>& t, const HierarchicalSpline<D>& h, int n, unsigned seed) {
  double worst = 0;
  std::vector<double> a(static_cast<std::size_t>(t.dim())), b(a.size());
  for (const auto& u : random_points<D>(n, seed)) {
    t.eval(u, a.data());
    h.eval(u, b.data());
    for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
  }
  return worst;
}

template <int D>
void check_nested(int p, int elements, bool rational, HierarchicalBasis basis, int steps) {
  const TensorSpline<D> t = generic_spline<D>(p, elements, 3, rational, 5);
  HierarchicalSpline<D> h(t, basis);
  EXPECT_LT(max_difference(t, h, 200, 1), 1e-14);
  for (int step = 0; step < steps; ++step) {
    refine_randomly(h, 1, 17 + static_cast<unsigned>(step));
    EXPECT_LT(max_difference(t, h, 300, 2 + static_cast<unsigned>(step)), 1e-12) << "after step " << step;
  }
  EXPECT_GE(h.space().num_levels(), steps);
  // The other basis over the same hierarchy holds the same spline.
  const HierarchicalSpline<D> other =
      h.with_basis(basis == HierarchicalBasis::thb ? HierarchicalBasis::hb : HierarchicalBasis::thb);
  EXPECT_LT(max_difference(t, other, 300, 9), 1e-12);
  EXPECT_LT(max_difference(t, other.with_basis(basis), 300, 10), 1e-12);
}

}  // namespace

TEST(HierarchicalSpline, RefinementKeepsSurfaces) {
  check_nested<2>(2, 4, false, HierarchicalBasis::thb, 5);
  check_nested<2>(3, 3, false, HierarchicalBasis::hb, 5);
  check_nested<2>(2, 3, true, HierarchicalBasis::thb, 4);
}

TEST(HierarchicalSpline, RefinementKeepsVolumes) {
  check_nested<3>(3, 3, false, HierarchicalBasis::thb, 3);
  check_nested<3>(2, 3, false, HierarchicalBasis::hb, 3);
  check_nested<3>(2, 2, true, HierarchicalBasis::thb, 3);
}

TEST(HierarchicalSpline, RefinementByFunctionsKeepsTheSpline) {
  const TensorSpline<3> t = generic_spline<3>(2, 3, 2, false, 8);
  HierarchicalSpline<3> h(t);
  for (int step = 0; step < 3; ++step) {
    const int N = h.space().num_basis();
    h.refine_functions(std::vector<int>{N / 3, N - 1});
    EXPECT_LT(max_difference(t, h, 200, 4), 1e-12);
  }
}

// Domains cutting coarser cells (G+Smo's boxes): Omega^1 = stripes of level-1 cells {1,2,3,5,6,7}^2 split every
// level-0 cell and cover none of those under the level-0 functions' supports in the first column, so no level-0
// function has a leaf of its own level; Omega^2 = level-2 cells [3, 7)^2 cuts level-1 cells again. The spline
// stays the tensor spline through the refinement, both bases and further refinement.
TEST(HierarchicalSpline, DomainsCuttingEveryCellOfASupportKeepTheSpline) {
  std::vector<Ints<2>> stripes, inner;
  for (int j : {1, 2, 3, 5, 6, 7})
    for (int i : {1, 2, 3, 5, 6, 7}) stripes.push_back({i, j});
  for (int j = 3; j < 7; ++j)
    for (int i = 3; i < 7; ++i) inner.push_back({i, j});
  for (bool rational : {false, true})
    for (auto basis : {HierarchicalBasis::thb, HierarchicalBasis::hb}) {
      const TensorSpline<2> t = generic_spline<2>(2, 4, 3, rational, 7);
      HierarchicalSpline<2> h(t, basis);
      EXPECT_EQ(h.extend_domains({{}, stripes, inner}), 36 + 16);
      EXPECT_FALSE(h.space().is_refined(0, {0, 0}));
      EXPECT_LT(h.space().find_leaf(0, {0, 0}), 0);
      EXPECT_LT(max_difference(t, h, 300, 3), 1e-12);
      const auto other = h.with_basis(basis == HierarchicalBasis::thb ? HierarchicalBasis::hb : HierarchicalBasis::thb);
      EXPECT_LT(max_difference(t, other, 300, 4), 1e-12);
      refine_randomly(h, 2, 5);
      EXPECT_LT(max_difference(t, h, 300, 6), 1e-12);
    }
}

TEST(HierarchicalSpline, MixedDegreesAndDeepCorner) {
  // Degrees (1, 3): ten levels at the corner u = 0.
  std::array<KnotVector, 2> kv{KnotVector::open_uniform(1, 3), KnotVector::open_uniform(3, 2)};
  const int n = kv[0].size() * kv[1].size();
  std::vector<double> c;
  for (int i = 0; i < n; ++i) c.insert(c.end(), {std::sin(i * 1.0), std::cos(i * 0.3)});
  const TensorSpline<2> t(kv, 2, false, c);
  HierarchicalSpline<2> h(t);
  for (int l = 0; l < 10; ++l) h.refine_elements(std::vector<int>{h.space().find_element(Param<2>{1e-9, 1e-9})});
  EXPECT_EQ(h.space().num_levels(), 11);
  EXPECT_LT(max_difference(t, h, 300, 3), 1e-12);
  std::vector<double> a(2), b(2);
  for (double x : {1e-5, 3e-4, 1e-3}) {
    t.eval({x, x}, a.data());
    h.eval({x, x}, b.data());
    EXPECT_NEAR(a[0], b[0], 1e-13);
  }
}

template <int D>
void check_derivatives(bool rational) {
  HierarchicalSpline<D> h(generic_spline<D>(3, 3, 2, rational, 12));
  refine_randomly(h, 3, 4);
  const int nd = derivative_count(D, 2);
  std::vector<double> d1((D + 1) * 2), all(static_cast<std::size_t>(nd) * 2), p1(d1.size()), m1(d1.size());
  const double step = 1e-6;
  int checked = 0;
  for (const auto& u : random_points<D>(100, 21)) {
    h.eval_first_derivatives(u, d1.data());
    h.eval_derivs(u, 2, all.data());
    for (int i = 0; i < (D + 1) * 2; ++i) EXPECT_NEAR(d1[static_cast<std::size_t>(i)], all[static_cast<std::size_t>(i)], 1e-12);
    for (int a = 0; a < D; ++a) {
      Param<D> up = u, um = u;
      up[a] += step;
      um[a] -= step;
      if (h.space().find_element(up) != h.space().find_element(u) || h.space().find_element(um) != h.space().find_element(u))
        continue;
      ++checked;
      h.eval_first_derivatives(up, p1.data());
      h.eval_first_derivatives(um, m1.data());
      for (int c = 0; c < 2; ++c) {
        const double fd = (p1[static_cast<std::size_t>(c)] - m1[static_cast<std::size_t>(c)]) / (2 * step);
        EXPECT_NEAR(d1[static_cast<std::size_t>((1 + a) * 2 + c)], fd, 1e-6 * (1 + std::abs(fd)));
        for (int b = 0; b < D; ++b) {
          Ints<D> alpha{};
          ++alpha[a];
          ++alpha[b];
          const double fd2 = (p1[static_cast<std::size_t>((1 + b) * 2 + c)] - m1[static_cast<std::size_t>((1 + b) * 2 + c)]) / (2 * step);
          EXPECT_NEAR(all[static_cast<std::size_t>(derivative_position<D>(alpha) * 2 + c)], fd2, 1e-4 * (1 + std::abs(fd2)));
        }
      }
    }
  }
  EXPECT_GT(checked, 100);
}

TEST(HierarchicalSpline, DerivativesMatchFiniteDifferences) {
  check_derivatives<2>(false);
  check_derivatives<2>(true);
  check_derivatives<3>(false);
  check_derivatives<3>(true);
}

TEST(HierarchicalSpline, BezierElementsReproduceTheSpline) {
  HierarchicalSpline<3> h(generic_spline<3>(2, 3, 3, true, 2));
  refine_randomly(h, 2, 6);
  const auto nets = h.bezier_elements();
  ASSERT_EQ(static_cast<int>(nets.size()), h.space().num_elements());
  std::vector<double> a(3);
  for (const auto& u : random_points<3>(100, 8)) {
    const int e = h.space().find_element(u);
    const auto& net = nets[static_cast<std::size_t>(e)];
    ASSERT_TRUE(net.domain.contains(u));
    h.eval(u, a.data());
    std::vector<double> b(3);
    eval_bezier(net, u, b.data());
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(b[static_cast<std::size_t>(c)], a[static_cast<std::size_t>(c)], 1e-13);
  }
}

TEST(HierarchicalSpline, ManyPointsAreBitIdenticalForAnyThreadCount) {
  HierarchicalSpline<3> h(generic_spline<3>(3, 4, 3, false, 2));
  refine_randomly(h, 3, 6);
  const auto pts = random_points<3>(2000, 3);
  std::vector<double> one(pts.size() * 3), two(pts.size() * 3), single(3);
  h.eval_many(pts, one, 1);
  h.eval_many(pts, two, 2);
  EXPECT_EQ(one, two);
  h.eval(pts[17], single.data());
  EXPECT_EQ(single[0], one[51]);
}

TEST(HierarchicalSpline, BadInputThrows) {
  HierarchicalSpline<2> h(generic_spline<2>(2, 2, 1, false));
  EXPECT_THROW(HierarchicalSpline<2>(h.space(), 1, false, std::vector<double>(3)), Error);
  EXPECT_THROW(HierarchicalSpline<2>(h.space(), 0, false, {}), Error);
  std::vector<double> c(h.coefs().begin(), h.coefs().end());
  c[2] = std::nan("");
  EXPECT_THROW(HierarchicalSpline<2>(h.space(), 1, false, c), Error);
  const KnotVector unclamped(2, {0, 0.1, 0.2, 0.5, 0.8, 0.9, 1});
  EXPECT_THROW(TensorHierarchy<2>(std::array<KnotVector, 2>{unclamped, unclamped}), Error);
}
