// The exact tensor form of an LR spline: equal values at random points (by the two splines' own evaluators) for
// locally refined surfaces and volumes with scaled B-splines, the tensor knots the union of the mesh lines, and
// an LR spline that is a tensor spline given back with its own coefficients.
#include "trivar/lr/refinement.hpp"
#include "trivar/lr/tensor_expansion.hpp"
#include "trivar/spline/knot_vector.hpp"

namespace trivar::tensor_expansion_test {
namespace {

template <int D>
LRSpline<D> random_tensor(int degree, int elements, int dim, std::mt19937& rng) {
  std::uniform_real_distribution<double> c(-1.0, 1.0);
  std::array<KnotVector, D> knots;
  std::size_t count = 1;
  for (int k = 0; k < D; ++k) {
    knots[static_cast<std::size_t>(k)] = KnotVector::open_uniform(degree + (k == 1), elements + k, 0.0, 1.0 + k);
    count *= static_cast<std::size_t>(degree + (k == 1) + elements + k);
  }
  std::vector<double> coefs(count * static_cast<std::size_t>(dim));
  for (double& x : coefs) x = c(rng);
  return LRSpline<D>(TensorSpline<D>(std::move(knots), dim, false, std::move(coefs)));
}

template <int D>
void expect_same_values(const LRSpline<D>& lr, const TensorSpline<D>& t, std::mt19937& rng) {
  ASSERT_EQ(t.dim(), lr.dim());
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> a(static_cast<std::size_t>(lr.dim())), b(a.size());
  for (int i = 0; i < 300; ++i) {
    Param<D> x;
    for (int k = 0; k < D; ++k) x[k] = lr.domain().lo[k] + u(rng) * (lr.domain().hi[k] - lr.domain().lo[k]);
    lr.eval(x, a.data());
    t.eval(x, b.data());
    for (std::size_t c = 0; c < a.size(); ++c) ASSERT_NEAR(a[c], b[c], 1e-13) << i;
  }
}

TEST(TensorExpansion, LocallyRefinedSurfaceAndVolume) {
  std::mt19937 rng(7);
  LRSpline<2> s = random_tensor<2>(2, 4, 3, rng);
  refine_elements(s, std::span<const int>(std::vector<int>{0, 5}), RefineOptions{Strategy::minspan});
  refine_elements(s, std::span<const int>(std::vector<int>{2}), RefineOptions{Strategy::structured});
  ASSERT_TRUE(std::any_of(s.basis_functions().begin(), s.basis_functions().end(),
                          [](const LRBSpline<2>& b) { return b.gamma < 1.0; }));
  const TensorSpline<2> ts = tensor_expansion(s);
  expect_same_values(s, ts, rng);
  // The union of the knot lines: more tensor coefficients than LR B-splines.
  EXPECT_GT(ts.num_coefs(), s.num_basis());

  LRSpline<3> v = random_tensor<3>(2, 2, 2, rng);
  refine_elements(v, std::span<const int>(std::vector<int>{0, 3}), RefineOptions{Strategy::fullspan});
  refine_elements(v, std::span<const int>(std::vector<int>{1}), RefineOptions{Strategy::minspan});
  expect_same_values(v, tensor_expansion(v), rng);
}

TEST(TensorExpansion, ATensorSplineComesBackAsItWas) {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> c(-1.0, 1.0);
  const std::array<KnotVector, 3> knots = {KnotVector(2, {0, 0, 0, 0.3, 0.3, 1, 1, 1}),
                                           KnotVector(1, {0, 0, 0.5, 2, 2}), KnotVector::open_uniform(3, 2)};
  std::vector<double> coefs(5 * 3 * 5 * 2);
  for (double& x : coefs) x = c(rng);
  const TensorSpline<3> t(knots, 2, false, coefs);
  const TensorSpline<3> back = tensor_expansion(LRSpline<3>(t));
  for (int k = 0; k < 3; ++k) EXPECT_EQ(back.knots(k).knots(), t.knots(k).knots()) << k;
  ASSERT_EQ(back.coefs().size(), coefs.size());
  for (std::size_t i = 0; i < coefs.size(); ++i) EXPECT_EQ(back.coefs()[i], coefs[i]) << i;
}

}  // namespace
}  // namespace trivar::tensor_expansion_test
