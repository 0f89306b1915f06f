#include "trivar/spline/tensor_spline.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "support/spline_fixtures.hpp"
#include "trivar/core/error.hpp"
#include "trivar/spline/derivative_index.hpp"
#include "trivar/spline/jacobian.hpp"

using namespace trivar;

template <int D>
void check_against_reference(bool rational, bool clamped, unsigned seed) {
  Ints<D> deg, el;
  for (int k = 0; k < D; ++k) {
    deg[k] = 1 + (k + static_cast<int>(seed)) % 3;
    el[k] = 3 + k;
  }
  const auto s = test::random_spline<D>(deg, el, 3, rational, seed, clamped);
  std::vector<double> x(3);
  for (const auto& u : test::random_params(s, 200, seed + 1)) {
    s.eval(u, x.data());
    const auto r = test::reference_eval(s, u);
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(x[d], r[d], 1e-12);
  }
}

TEST(TensorSpline, EvaluationMatchesCoxDeBoorReference) {
  for (bool rational : {false, true})
    for (bool clamped : {true, false}) {
      check_against_reference<1>(rational, clamped, 1);
      check_against_reference<2>(rational, clamped, 2);
      check_against_reference<3>(rational, clamped, 3);
    }
}

TEST(TensorSpline, PartitionOfUnity) {
  auto s = test::random_spline<3>({3, 2, 4}, {4, 5, 3}, 1, false, 5);
  for (double& c : s.coefs()) c = 1.0;
  double x;
  for (const auto& u : test::random_params(s, 500, 9)) {
    s.eval(u, &x);
    EXPECT_NEAR(x, 1.0, 1e-14);
  }
  // The domain corners too (closed right end).
  s.eval({3.0, 2.0, 1.0}, &x);
  EXPECT_NEAR(x, 1.0, 1e-14);
}

template <int D>
void check_derivatives(bool rational, unsigned seed) {
  Ints<D> deg, el;
  for (int k = 0; k < D; ++k) {
    deg[k] = 2 + k % 2;
    el[k] = 3;
  }
  const auto s = test::random_spline<D>(deg, el, 2, rational, seed);
  const int order = 2;
  const int nd = derivative_count(D, order);
  const auto idx = derivative_multi_indices<D>(order);
  std::vector<double> f(nd * 2), fp(nd * 2), fm(nd * 2);
  const double h = 1e-5;
  for (const auto& u : test::random_params(s, 60, seed + 3)) {
    s.eval_derivs(u, order, f.data());
    std::vector<double> v(2);
    s.eval(u, v.data());
    EXPECT_NEAR(f[0], v[0], 1e-13);
    for (int k = 0; k < D; ++k) {
      auto up = u, um = u;
      up[k] += h;
      um[k] -= h;
      // Stay inside one element: skip points next to a knot in this direction.
      if (s.knots(k).find_span(up[k]) != s.knots(k).find_span(um[k]) || um[k] < s.domain().lo[k] ||
          up[k] > s.domain().hi[k])
        continue;
      s.eval_derivs(up, order, fp.data());
      s.eval_derivs(um, order, fm.data());
      // Every derivative a with a + e_k of order <= 2 is checked by central differences of a.
      for (int a = 0; a < derivative_count(D, order - 1); ++a) {
        auto b = idx[a];
        b[k] += 1;
        const int pb = derivative_position<D>(b);
        for (int d = 0; d < 2; ++d) {
          const double fd = (fp[a * 2 + d] - fm[a * 2 + d]) / (2 * h);
          EXPECT_NEAR(f[pb * 2 + d], fd, 2e-5 * (1 + std::abs(fd))) << "D=" << D << " deriv " << pb;
        }
      }
    }
  }
}

TEST(TensorSpline, DerivativesMatchFiniteDifferences) {
  for (bool rational : {false, true}) {
    check_derivatives<1>(rational, 21);
    check_derivatives<2>(rational, 22);
    check_derivatives<3>(rational, 23);
  }
}

TEST(TensorSpline, DerivativeOrderingIsGraded) {
  const auto idx = derivative_multi_indices<3>(2);
  ASSERT_EQ(idx.size(), 10u);
  EXPECT_EQ(idx[1], (std::array<int, 3>{1, 0, 0}));
  EXPECT_EQ(idx[3], (std::array<int, 3>{0, 0, 1}));
  EXPECT_EQ(idx[5], (std::array<int, 3>{1, 1, 0}));
  EXPECT_EQ(idx[9], (std::array<int, 3>{0, 0, 2}));
  for (int i = 0; i < static_cast<int>(idx.size()); ++i) EXPECT_EQ(derivative_position<3>(idx[i]), i);
  const auto big = derivative_multi_indices<2>(5);
  for (int i = 0; i < static_cast<int>(big.size()); ++i) EXPECT_EQ(derivative_position<2>(big[i]), i);
}

TEST(TensorSpline, RationalQuarterCircleHasExactRadius) {
  const double w = std::sqrt(0.5);
  const double pts[] = {1, 0, 1, 1, 0, 1};
  const double wts[] = {1, w, 1};
  const auto c = SplineCurve::from_cartesian({KnotVector(2, {0, 0, 0, 1, 1, 1})}, 2, pts, wts);
  double x[2 * 3];
  for (int q = 0; q <= 1000; ++q) {
    c.eval({q / 1000.0}, x);
    EXPECT_NEAR(std::hypot(x[0], x[1]), 1.0, 1e-15);
    // The tangent is perpendicular to the radius.
    c.eval_derivs({q / 1000.0}, 2, x);
    EXPECT_NEAR(x[0] * x[2] + x[1] * x[3], 0.0, 1e-14);
  }
}

TEST(TensorSpline, BatchAndGridMatchPointwiseForAnyThreadCount) {
  const auto s = test::random_spline<3>({3, 3, 2}, {4, 3, 5}, 3, true, 31);
  const auto u = test::random_params(s, 2000, 32);
  std::vector<double> one(u.size() * 3), many(u.size() * 3), x(3);
  s.eval_batch(u, one, 1);
  s.eval_batch(u, many, 2);
  for (std::size_t i = 0; i < u.size(); ++i) {
    s.eval(u[i], x.data());
    for (int d = 0; d < 3; ++d) {
      EXPECT_EQ(one[i * 3 + d], x[d]);
      EXPECT_EQ(many[i * 3 + d], x[d]);
    }
  }
  std::vector<double> d1(u.size() * 30), d2(u.size() * 30);
  s.eval_derivs_batch(u, 2, d1, 1);
  s.eval_derivs_batch(u, 2, d2, 2);
  EXPECT_EQ(d1, d2);

  std::array<std::vector<double>, 3> g{std::vector<double>{0, 0.1, 0.5, 0.77, 1.0},
                                       std::vector<double>{0, 1.3, 2.0}, std::vector<double>{0, 0.25, 2.5, 3.0}};
  std::vector<double> grid(5 * 3 * 4 * 3), grid2(grid.size());
  s.eval_grid(g, grid, 1);
  s.eval_grid(g, grid2, 2);
  EXPECT_EQ(grid, grid2);
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 5; ++i) {
        s.eval({g[0][i], g[1][j], g[2][k]}, x.data());
        for (int d = 0; d < 3; ++d) EXPECT_NEAR(grid[((k * 3 + j) * 5 + i) * 3 + d], x[d], 1e-13);
      }
}

TEST(TensorSpline, PolynomialGridMatchesPointwise) {
  const auto s = test::random_spline<2>({2, 3}, {3, 4}, 1, false, 41);
  std::array<std::vector<double>, 2> g{std::vector<double>{0, 0.3, 1.0}, std::vector<double>{0.1, 1.9}};
  std::vector<double> grid(6);
  s.eval_grid(g, grid);
  double x;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i) {
      s.eval({g[0][i], g[1][j]}, &x);
      EXPECT_NEAR(grid[j * 3 + i], x, 1e-14);
    }
}

TEST(TensorSpline, ConstructorRejectsBadInput) {
  const KnotVector kv(1, {0, 0, 1, 1});
  EXPECT_THROW(SplineCurve({kv}, 2, false, {0, 0, 1}), Error);
  EXPECT_THROW(SplineCurve({kv}, 0, false, {}), Error);
  EXPECT_THROW(SplineCurve({kv}, 1, true, {0, 1, 1, -1}), Error);
  EXPECT_THROW(SplineCurve({kv}, 1, false, {0, NAN}), Error);
}

TEST(TensorSpline, SpecialisedKernelsMatchTheGeneralPath) {
  // Equal degrees 1..3 with control dimension 1 or 3 (polynomial and rational) take the compile-time kernels;
  // order 2 always takes the general path, whose first entries are the value and first derivatives.
  for (int p = 1; p <= 3; ++p)
    for (int dim : {1, 3})
      for (bool rational : {false, true}) {
        const auto s = test::random_spline<3>({p, p, p}, {3, 4, 2}, dim, rational, 50 + p);
        std::vector<double> d1(4 * dim), d2(10 * dim);
        for (const auto& u : test::random_params(s, 100, 51)) {
          s.eval_derivs(u, 1, d1.data());
          s.eval_derivs(u, 2, d2.data());
          const auto ref = test::reference_eval(s, u);
          for (int i = 0; i < 4 * dim; ++i) EXPECT_NEAR(d1[i], d2[i], 1e-11 * (1 + std::abs(d2[i])));
          for (int d = 0; d < dim; ++d) EXPECT_NEAR(d1[d], ref[d], 1e-12);
        }
      }
}

namespace {

// The unit cube as a trilinear volume with every weight equal to w (equal weights cancel: the geometry is the
// polynomial cube whatever w is, and det J = 1 everywhere).
SplineVolume weighted_cube(const std::vector<double>& w) {
  const KnotVector kv(1, {0, 0, 1, 1});
  std::vector<double> pts;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) pts.insert(pts.end(), {double(i), double(j), double(k)});
  return SplineVolume::from_cartesian({kv, kv, kv}, 3, pts, w);
}

std::string weight_error(const std::vector<double>& w) {
  try {
    weighted_cube(w);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(TensorSpline, WeightsMustKeepRationalEvaluationInRange) {
  EXPECT_EQ(weight_error(std::vector<double>(8, 1e-320)),
            "spline: the largest weight 1e-320 (control point 0) is outside [1e-50, 1e+50]; scale all weights by a "
            "common factor, which leaves the geometry unchanged");
  std::vector<double> w(8, 1.0);
  w[5] = 1e-13;
  EXPECT_EQ(weight_error(w), "spline: weight of control point 5 is 1e-13, less than 1e-12 times the largest weight 1 "
                             "(control point 0)");
  w[5] = 0;
  EXPECT_EQ(weight_error(w), "spline: weight of control point 5 is 0; weights must be positive");
  w[5] = INFINITY;
  EXPECT_THROW(weighted_cube(w), Error);
  // Inside the bounds, a common factor changes nothing: the cube with det J = 1.
  for (double scale : {1e-40, 1.0, 1e40}) {
    const SplineVolume v = weighted_cube(std::vector<double>(8, scale));
    double x[3];
    v.eval({0.25, 0.5, 0.75}, x);
    EXPECT_NEAR(x[0], 0.25, 1e-15);
    EXPECT_NEAR(x[1], 0.5, 1e-15);
    EXPECT_NEAR(x[2], 0.75, 1e-15);
    const auto rep = check_jacobian(v);
    EXPECT_NEAR(rep.min_value, 1.0, 1e-12) << "scale " << scale;
    EXPECT_LE(rep.min_lower_bound, 1.0 + 1e-12);
    EXPECT_GE(rep.min_lower_bound, 1.0 - 1e-9);
  }
}
