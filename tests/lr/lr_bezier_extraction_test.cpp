#include "trivar/lr/lr_bezier_extraction.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "support/spline_fixtures.hpp"
#include "trivar/core/error.hpp"

using namespace trivar;

namespace {

// Every tensor B-spline as a scaled B-spline (gamma 1, its local knots), and the elements (u fastest), built
// here from the knot vectors so that the test does not depend on LRSpline.
template <int D>
struct TensorCollection {
  std::vector<LRBSpline<D>> basis;
  std::vector<Box<D>> elements;
};

template <int D>
TensorCollection<D> tensor_collection(const TensorSpline<D>& s) {
  TensorCollection<D> c;
  for (int l = 0; l < s.num_coefs(); ++l) {
    const auto idx = s.multi_index(l);
    LRBSpline<D> b;
    for (int k = 0; k < D; ++k) {
      const auto& t = s.knots(k).knots();
      b.knots[k].assign(t.begin() + idx[k], t.begin() + idx[k] + s.degree(k) + 2);
    }
    b.coef.assign(s.coef(l), s.coef(l) + s.stride());
    c.basis.push_back(std::move(b));
  }
  std::array<std::vector<double>, D> bp;
  int total = 1;
  for (int k = 0; k < D; ++k) {
    bp[k] = s.knots(k).breakpoints();
    total *= static_cast<int>(bp[k].size()) - 1;
  }
  for (int e = 0; e < total; ++e) {
    Box<D> box;
    int r = e;
    for (int k = 0; k < D; ++k) {
      const int n = static_cast<int>(bp[k].size()) - 1, i = r % n;
      r /= n;
      box.lo[k] = bp[k][i];
      box.hi[k] = bp[k][i + 1];
    }
    c.elements.push_back(box);
  }
  return c;
}

// sum_i gamma_i c_i B_i(u) by the Cox-de Boor recursion on the local knots (homogeneous values).
template <int D>
std::vector<double> direct_sum(const std::vector<LRBSpline<D>>& basis, const Param<D>& u, int stride) {
  std::vector<double> out(static_cast<std::size_t>(stride), 0.0);
  for (const auto& b : basis) {
    double v = b.gamma;
    for (int k = 0; k < D; ++k)
      v *= test::cox_de_boor(b.knots[k], 0, static_cast<int>(b.knots[k].size()) - 2, u[k], b.knots[k].back());
    for (int s = 0; s < stride; ++s) out[static_cast<std::size_t>(s)] += v * b.coef[static_cast<std::size_t>(s)];
  }
  return out;
}

template <int D>
Param<D> random_in(const Box<D>& b, std::mt19937& rng) {
  Param<D> u;
  for (int k = 0; k < D; ++k) u[k] = std::uniform_real_distribution<double>(b.lo[k], b.hi[k])(rng);
  return u;
}

template <int D>
void check_tensor(const Ints<D>& degrees, const Ints<D>& elements, bool rational, unsigned seed) {
  const auto s = test::random_spline<D>(degrees, elements, 3, rational, seed);
  const auto c = tensor_collection(s);
  const auto ours = bezier_elements<D>(degrees, c.basis, c.elements, s.dim(), s.is_rational());
  const auto ref = bezier_elements(s);
  ASSERT_EQ(ours.size(), ref.size());
  std::mt19937 rng(seed + 1);
  const Incidence on = element_supports<D>(c.basis, c.elements);
  int P = 1;
  for (int k = 0; k < D; ++k) P *= degrees[k] + 1;
  for (std::size_t e = 0; e < ours.size(); ++e) {
    // Same Bezier nets as the tensor-product extraction.
    ASSERT_EQ(ours[e].coefs.size(), ref[e].coefs.size());
    for (std::size_t i = 0; i < ours[e].coefs.size(); ++i) EXPECT_NEAR(ours[e].coefs[i], ref[e].coefs[i], 1e-13);
    // Bernstein evaluation equals the direct B-spline sum.
    std::vector<double> x(static_cast<std::size_t>(s.stride()));
    for (int q = 0; q < 5; ++q) {
      const auto u = random_in(c.elements[e], rng);
      const auto d = direct_sum(c.basis, u, s.stride());
      eval_bezier(ours[e], u, x.data());
      const std::vector<double> h = d;
      for (int j = 0; j < s.dim(); ++j) {
        const double want = rational ? h[static_cast<std::size_t>(j)] / h[static_cast<std::size_t>(s.dim())] : h[static_cast<std::size_t>(j)];
        EXPECT_NEAR(x[static_cast<std::size_t>(j)], want, 1e-13);
      }
    }
    // (p+1)^D B-splines per element of a tensor mesh; the columns of C sum to one (partition of unity).
    const auto ids = on[static_cast<int>(e)];
    EXPECT_EQ(static_cast<int>(ids.size()), P);
    const Eigen::MatrixXd C = extraction_operator<D>(degrees, c.basis, ids, c.elements[e]);
    EXPECT_NEAR((C.colwise().sum().array() - 1.0).abs().maxCoeff(), 0.0, 1e-14);
  }
}

}  // namespace

TEST(LRBezierExtraction, TensorCollectionMatchesTensorExtraction) {
  for (bool rational : {false, true}) {
    check_tensor<2>({3, 2}, {4, 3}, rational, 31);
    check_tensor<2>({1, 4}, {3, 2}, rational, 32);
    check_tensor<3>({2, 1, 3}, {3, 2, 2}, rational, 33);
  }
}

TEST(LRBezierExtraction, ElementSupportsFindExactlyTheContainingSupports) {
  const auto s = test::random_spline<3>({2, 3, 1}, {5, 4, 6}, 1, false, 41);
  const auto c = tensor_collection(s);
  const Incidence on = element_supports<3>(c.basis, c.elements, 2);
  for (int e = 0; e < on.size(); ++e) {
    std::vector<int> brute;
    for (std::size_t b = 0; b < c.basis.size(); ++b) {
      const auto sup = c.basis[b].support();
      bool in = true;
      for (int k = 0; k < 3; ++k) in = in && sup.lo[k] <= c.elements[e].lo[k] && c.elements[e].hi[k] <= sup.hi[k];
      if (in) brute.push_back(static_cast<int>(b));
    }
    const auto got = on[e];
    EXPECT_EQ(std::vector<int>(got.begin(), got.end()), brute);
  }
}
