#include "trivar/spline/bernstein.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "trivar/core/error.hpp"

using namespace trivar;

namespace {

double binom(int n, int k) {
  double r = 1;
  for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
  return r;
}

// Reference: the defining sum with std::pow, term by term.
template <int D>
double direct(const Bernstein<D>& f, const Param<D>& t) {
  double s = 0;
  for (int q = 0; q < f.size(); ++q) {
    int r = q;
    double b = 1;
    for (int k = 0; k < D; ++k) {
      const int n = f.degree(k), i = r % (n + 1);
      r /= n + 1;
      b *= binom(n, i) * std::pow(t[k], i) * std::pow(1 - t[k], n - i);
    }
    s += f.coefs()[q] * b;
  }
  return s;
}

template <int D>
Bernstein<D> random_poly(const Ints<D>& n, std::mt19937& rng) {
  Bernstein<D> f(n);
  std::uniform_real_distribution<double> U(-1, 1);
  for (double& c : f.coefs()) c = U(rng);
  return f;
}

template <int D>
std::vector<Param<D>> random_points(int count, std::mt19937& rng) {
  std::uniform_real_distribution<double> U(0, 1);
  std::vector<Param<D>> out(count);
  for (auto& t : out)
    for (auto& x : t) x = U(rng);
  return out;
}

template <int D>
void check_arithmetic(const Ints<D>& n, const Ints<D>& m, unsigned seed) {
  std::mt19937 rng(seed);
  const auto a = random_poly<D>(n, rng), b = random_poly<D>(m, rng);
  const auto prod = a * b, sum = a + b, diff = a - b;
  for (int k = 0; k < D; ++k) {
    EXPECT_EQ(prod.degree(k), n[k] + m[k]);
    EXPECT_EQ(sum.degree(k), std::max(n[k], m[k]));
  }
  for (const auto& t : random_points<D>(50, rng)) {
    const double fa = direct(a, t), fb = direct(b, t);
    EXPECT_NEAR(a.eval(t), fa, 1e-14);
    EXPECT_NEAR(direct(prod, t), fa * fb, 1e-13);
    EXPECT_NEAR(direct(sum, t), fa + fb, 1e-13);
    EXPECT_NEAR(direct(diff, t), fa - fb, 1e-13);
  }
}

}  // namespace

TEST(Bernstein, EvaluationMatchesDefinition) {
  std::mt19937 rng(1);
  const auto f1 = random_poly<1>({5}, rng);
  const auto f2 = random_poly<2>({3, 0}, rng);
  const auto f3 = random_poly<3>({2, 4, 1}, rng);
  for (const auto& t : random_points<1>(20, rng)) EXPECT_NEAR(f1.eval(t), direct(f1, t), 1e-14);
  for (const auto& t : random_points<2>(20, rng)) EXPECT_NEAR(f2.eval(t), direct(f2, t), 1e-14);
  for (const auto& t : random_points<3>(20, rng)) EXPECT_NEAR(f3.eval(t), direct(f3, t), 1e-14);
}

TEST(Bernstein, ProductSumDifferenceMatchPointwise) {
  check_arithmetic<1>({3}, {4}, 2);
  check_arithmetic<2>({2, 3}, {1, 0}, 3);
  check_arithmetic<3>({2, 1, 3}, {1, 3, 0}, 4);
  check_arithmetic<3>({3, 3, 3}, {2, 3, 3}, 5);
}

TEST(Bernstein, ProductOfLinearFactorsHasKnownCoefficients) {
  // t * (1 - t) = B_1^2 / 2: coefficients (0, 1/2, 0).
  const Bernstein<1> t({1}, std::vector<double>{0, 1}), s({1}, std::vector<double>{1, 0});
  const auto p = t * s;
  ASSERT_EQ(p.size(), 3);
  EXPECT_DOUBLE_EQ(p.coefs()[0], 0.0);
  EXPECT_DOUBLE_EQ(p.coefs()[1], 0.5);
  EXPECT_DOUBLE_EQ(p.coefs()[2], 0.0);
}

TEST(Bernstein, ElevationKeepsValues) {
  std::mt19937 rng(6);
  const auto f = random_poly<3>({1, 2, 0}, rng);
  const auto g = f.elevate({4, 2, 3});
  EXPECT_EQ(g.degrees(), (Ints<3>{4, 2, 3}));
  for (const auto& t : random_points<3>(50, rng)) EXPECT_NEAR(direct(g, t), direct(f, t), 1e-14);
  EXPECT_THROW(f.elevate({0, 2, 0}), Error);
}

TEST(Bernstein, DerivativeMatchesFiniteDifferences) {
  std::mt19937 rng(7);
  const auto f = random_poly<3>({3, 2, 1}, rng);
  const double h = 1e-6;
  for (int k = 0; k < 3; ++k) {
    const auto d = f.derivative(k);
    EXPECT_EQ(d.degree(k), f.degree(k) - 1);
    for (const auto& t : random_points<3>(30, rng)) {
      Param<3> a = t, b = t;
      a[k] -= h;
      b[k] += h;
      EXPECT_NEAR(direct(d, t), (direct(f, b) - direct(f, a)) / (2 * h), 1e-7);
    }
  }
  // Degree 0 in a direction: the derivative there is identically zero.
  const auto g = random_poly<2>({2, 0}, rng).derivative(1);
  EXPECT_EQ(g.degrees(), (Ints<2>{2, 0}));
  for (double c : g.coefs()) EXPECT_EQ(c, 0.0);
}

TEST(Bernstein, SubdivisionReparametrisesPieces) {
  std::mt19937 rng(8);
  const auto f = random_poly<3>({3, 4, 2}, rng);
  std::uniform_real_distribution<double> U(0.05, 0.95);
  for (int k = 0; k < 3; ++k) {
    const double c = U(rng);
    const auto [left, right] = f.subdivide(k, c);
    for (const auto& t : random_points<3>(30, rng)) {
      Param<3> a = t, b = t;
      a[k] = c * t[k];
      b[k] = c + (1 - c) * t[k];
      EXPECT_NEAR(direct(left, t), direct(f, a), 1e-13);
      EXPECT_NEAR(direct(right, t), direct(f, b), 1e-13);
    }
  }
}

TEST(Bernstein, CoefficientsBoundValuesAndCornersAreValues) {
  std::mt19937 rng(9);
  const auto f = random_poly<3>({2, 3, 2}, rng);
  const double lo = f.min_coef(), hi = f.max_coef();
  for (const auto& t : random_points<3>(200, rng)) {
    const double v = direct(f, t);
    EXPECT_LE(lo, v);
    EXPECT_GE(hi, v);
  }
  for (int c = 0; c < 8; ++c) {
    const Param<3> t{double(c & 1), double(c >> 1 & 1), double(c >> 2 & 1)};
    EXPECT_NEAR(f.corner(c), direct(f, t), 1e-15);
  }
}

TEST(Bernstein, VariationIsLargestNeighbourDifference) {
  const Bernstein<2> f({2, 1}, std::vector<double>{0, 1, 5, 0, 0.5, 1});
  EXPECT_DOUBLE_EQ(f.variation(0), 4.0);
  EXPECT_DOUBLE_EQ(f.variation(1), 4.0);
  const Bernstein<2> g({2, 1}, std::vector<double>{0, 1, 2, 0, 1, 2});
  EXPECT_DOUBLE_EQ(g.variation(0), 1.0);
  EXPECT_DOUBLE_EQ(g.variation(1), 0.0);
}

TEST(Bernstein, RejectsBadSizes) {
  EXPECT_THROW(Bernstein<2>({1, 1}, std::vector<double>{1, 2, 3}), Error);
  EXPECT_THROW(Bernstein<1>(Ints<1>{-1}), Error);
}
