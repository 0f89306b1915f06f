// Scattered-data approximation by LR splines: reproduction of splines in the space, the tolerance met at every
// point (checked by evaluating the result with the LR spline's own evaluator, not the fit's Bernstein path),
// local refinement around a crater rim, noise, volumes and material fractions, the three strategies.
#include <gtest/gtest.h>

#include <random>

#include "trivar/core/error.hpp"
#include "trivar/fit/graph_surface.hpp"
#include "trivar/fit/least_squares.hpp"
#include "trivar/fit/lr_approximation.hpp"
#include "trivar/lr/linear_independence.hpp"
#include "trivar/lr/refinement.hpp"
#include "fit/crater.hpp"

namespace trivar {
namespace {

// Franke's test function on [0, 1]^2 (Franke 1979).
double franke(double x, double y) {
  return 0.75 * std::exp(-(std::pow(9 * x - 2, 2) + std::pow(9 * y - 2, 2)) / 4) +
         0.75 * std::exp(-std::pow(9 * x + 1, 2) / 49 - (9 * y + 1) / 10) +
         0.5 * std::exp(-(std::pow(9 * x - 7, 2) + std::pow(9 * y - 3, 2)) / 4) -
         0.2 * std::exp(-std::pow(9 * x - 4, 2) - std::pow(9 * y - 7, 2));
}

using test::crater;
using test::kCx;
using test::kCy;
using test::kR;

template <int D, class F>
ScatteredData<D> sample(std::size_t n, int dim, std::uint32_t seed, F&& f) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  ScatteredData<D> d;
  d.dim = dim;
  d.params.resize(n);
  d.values.resize(n * static_cast<std::size_t>(dim));
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k < D; ++k) d.params[i][k] = u(rng);
    f(d.params[i], d.values.data() + i * static_cast<std::size_t>(dim), rng);
  }
  return d;
}

// Largest |s(x_i) - f_i| by the spline's evaluator.
template <int D>
double max_error(const LRSpline<D>& s, const ScatteredData<D>& d) {
  std::vector<double> v(d.size() * static_cast<std::size_t>(d.dim));
  s.eval_many(d.params, v, 1);
  double e = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i) e = std::max(e, std::abs(v[i] - d.values[i]));
  return e;
}

TEST(LeastSquares, ReproducesALocallyRefinedSplineInTheSpace) {
  ApproximationOptions o;
  o.initial_elements = 4;
  o.tolerance = 1.0;
  LRSpline<2> space = initial_space<2>(Box<2>{{0, 0}, {1, 1}}, o);
  const std::vector<int> corner = {0, 1, 4};
  refine_elements(space, std::span<const int>(corner), RefineOptions{});
  refine_elements(space, std::span<const int>(std::vector<int>{0}), RefineOptions{Strategy::minspan});
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> c(-1.0, 1.0);
  std::vector<double> coefs(static_cast<std::size_t>(space.num_basis()));
  for (double& x : coefs) x = c(rng);
  const LRSpline<2> truth = with_coefficients(space, 1, coefs);
  ScatteredData<2> d = sample<2>(4000, 1, 5, [&](const Param<2>& p, double* v, auto&) { truth.eval(p, v); });
  const PointsByElement where = locate_points(space, std::span<const Param<2>>(d.params));
  const LeastSquaresResult r = least_squares_fit(space, d, where, 0.0);
  for (std::size_t i = 0; i < coefs.size(); ++i) EXPECT_NEAR(r.coefs[i], coefs[i], 1e-10) << i;
  for (double e : r.errors) EXPECT_LT(e, 1e-12);
  EXPECT_LT(max_error(with_coefficients(space, 1, r.coefs), d), 1e-12);
}

TEST(LrApproximation, ReproducesATensorSplineAtLevelZero) {
  ApproximationOptions o;
  o.initial_elements = 3;
  o.degree = 3;
  o.tolerance = 1e-12;
  o.smoothing = 0.0;
  const LRSpline<3> space = initial_space<3>(Box<3>{{0, 0, 0}, {1, 1, 1}}, o);
  std::vector<double> coefs(static_cast<std::size_t>(space.num_basis()));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> c(-1.0, 1.0);
  for (double& x : coefs) x = c(rng);
  const LRSpline<3> truth = with_coefficients(space, 1, coefs);
  // Sampled at the corners too, so the bounding box is the unit cube and the fit's space is `space`.
  ScatteredData<3> d = sample<3>(5000, 1, 11, [&](const Param<3>& p, double* v, auto&) { truth.eval(p, v); });
  for (int k = 0; k < 8; ++k) {
    d.params[static_cast<std::size_t>(k)] = {double(k & 1), double((k >> 1) & 1), double(k >> 2)};
    truth.eval(d.params[static_cast<std::size_t>(k)], &d.values[static_cast<std::size_t>(k)]);
  }
  const Approximation<3> a = approximate(d, o);
  ASSERT_EQ(a.iterations.size(), 1u);
  EXPECT_TRUE(a.converged);
  EXPECT_LT(max_error(a.spline, d), 1e-12);
}

TEST(LrApproximation, FrankeMeetsTheToleranceAtEveryPoint) {
  const ScatteredData<2> d = sample<2>(20000, 1, 1, [](const Param<2>& p, double* v, auto&) { v[0] = franke(p[0], p[1]); });
  ApproximationOptions o;
  o.tolerance = 1e-3;
  o.max_levels = 10;
  const Approximation<2> a = approximate(d, o);
  EXPECT_TRUE(a.converged) << a.stop_reason;
  EXPECT_LE(max_error(a.spline, d), o.tolerance * (1 + 1e-9));
  for (std::size_t i = 1; i < a.iterations.size(); ++i) {
    EXPECT_GT(a.iterations[i].coefficients, a.iterations[i - 1].coefficients);
    EXPECT_EQ(a.iterations[i].independence, "independent");
  }
  EXPECT_EQ(peeling_test(a.spline).status, Independence::independent);
}

TEST(LrApproximation, CraterRefinesOnlyNearTheRim) {
  ScatteredData<2> d = sample<2>(15000, 1, 2, [](const Param<2>& p, double* v, auto&) { v[0] = crater(p[0], p[1]); });
  for (int k = 0; k < 4; ++k) {  // the corners, so the initial elements are 1/16 wide
    d.params[static_cast<std::size_t>(k)] = {double(k & 1), double(k >> 1)};
    d.values[static_cast<std::size_t>(k)] = crater(k & 1, k >> 1);
  }
  for (Strategy s : {Strategy::fullspan, Strategy::minspan, Strategy::structured}) {
    ApproximationOptions o;
    o.tolerance = 0.005 * 0.33;  // 0.5 % of the height range
    o.initial_elements = 16;
    o.max_levels = 12;
    o.strategy = s;
    const Approximation<2> a = approximate(d, o);
    EXPECT_TRUE(a.converged) << to_string(s) << ": " << a.stop_reason;
    EXPECT_LE(max_error(a.spline, d), o.tolerance * (1 + 1e-9)) << to_string(s);
    // Elements away from the crater keep the initial size 1/16: the refinement is local. (The first fit's
    // least-squares ripples exceed the tolerance up to two elements beyond the rim, so those are refined too.)
    int far = 0;
    double reach = 0.0;
    for (const Box<2>& e : a.spline.elements()) {
      const double dx = std::max({kCx - e.hi[0], e.lo[0] - kCx, 0.0}), dy = std::max({kCy - e.hi[1], e.lo[1] - kCy, 0.0});
      const double dist = std::hypot(dx, dy) - kR;
      if (e.hi[0] - e.lo[0] < 0.0625 - 1e-12 || e.hi[1] - e.lo[1] < 0.0625 - 1e-12) reach = std::max(reach, dist);
      else ++far;
    }
    EXPECT_LT(reach, 0.4) << to_string(s);
    EXPECT_GT(far, 60) << to_string(s);
    std::printf("%s: %d coefficients, refinement reaches %.3f beyond the rim\n", to_string(s), a.spline.num_basis(), reach);
  }
}

TEST(LrApproximation, SameResultOnOneOrTwoThreads) {
  const ScatteredData<2> d = sample<2>(8000, 1, 15, [](const Param<2>& p, double* v, auto&) { v[0] = crater(p[0], p[1]); });
  ApproximationOptions o;
  o.tolerance = 0.005;
  const Approximation<2> one = approximate(d, o);
  o.threads = 2;
  const Approximation<2> two = approximate(d, o);
  ASSERT_EQ(one.spline.num_basis(), two.spline.num_basis());
  for (int i = 0; i < one.spline.num_basis(); ++i)
    EXPECT_EQ(one.spline.basis_function(i).coef, two.spline.basis_function(i).coef) << i;
  EXPECT_EQ(one.errors, two.errors);
}

TEST(LrApproximation, NoisyDataWithinATolerableBand) {
  const ScatteredData<2> d = sample<2>(20000, 1, 4, [](const Param<2>& p, double* v, auto& rng) {
    std::uniform_real_distribution<double> noise(-0.005, 0.005);
    v[0] = franke(p[0], p[1]) + noise(rng);
  });
  ApproximationOptions o;
  o.tolerance = 0.02;
  const Approximation<2> a = approximate(d, o);
  EXPECT_TRUE(a.converged) << a.stop_reason;
  EXPECT_LE(max_error(a.spline, d), o.tolerance * (1 + 1e-9));
  // The noise is not chased: the fit stays far coarser than one coefficient per few points.
  EXPECT_LT(a.spline.num_basis(), 2000);
}

TEST(LrApproximation, VolumetricScalarField) {
  const ScatteredData<3> d = sample<3>(12000, 1, 6, [](const Param<3>& p, double* v, auto&) {
    const double r2 = std::pow(p[0] - 0.7, 2) + std::pow(p[1] - 0.3, 2) + std::pow(p[2] - 0.5, 2);
    v[0] = p[0] + 0.5 * p[1] * p[2] + std::exp(-r2 / 0.01);
  });
  ApproximationOptions o;
  o.tolerance = 0.02;
  o.initial_elements = 3;
  const Approximation<3> a = approximate(d, o);
  EXPECT_TRUE(a.converged) << a.stop_reason;
  EXPECT_LE(max_error(a.spline, d), o.tolerance * (1 + 1e-9));
  EXPECT_GT(a.iterations.size(), 1u);
  for (const IterationReport& r : a.iterations) EXPECT_EQ(r.independence, "independent");
  EXPECT_EQ(exact_test(a.spline).status, Independence::independent);
}

TEST(LrApproximation, MaterialFractionsKeepTheirSum) {
  // Three fractions from a graded blend with a sharp inclusion; they sum to one at every sample.
  const ScatteredData<3> d = sample<3>(6000, 3, 8, [](const Param<3>& p, double* v, auto&) {
    const double inc = std::hypot(p[0] - 0.5, p[1] - 0.5, p[2] - 0.5) < 0.2 ? 0.6 : 0.0;
    v[0] = (1 - inc) * p[2];
    v[1] = (1 - inc) * (1 - p[2]);
    v[2] = inc;
  });
  ApproximationOptions o;
  o.tolerance = 0.05;
  o.initial_elements = 2;
  o.max_levels = 2;
  const Approximation<3> a = approximate(d, o);
  EXPECT_EQ(a.spline.dim(), 3);
  // Constants lie in the space and have no energy, so the fitted fractions sum to one everywhere.
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 1000; ++i) {
    double v[3];
    a.spline.eval({u(rng), u(rng), u(rng)}, v);
    EXPECT_NEAR(v[0] + v[1] + v[2], 1.0, 1e-10);
  }
  EXPECT_LT(a.iterations.back().max_error, a.iterations.front().max_error);
}

TEST(LrApproximation, CoefficientLimitStopsBeforeExceedingIt) {
  const ScatteredData<2> d = sample<2>(5000, 1, 10, [](const Param<2>& p, double* v, auto&) { v[0] = crater(p[0], p[1]); });
  ApproximationOptions o;
  o.tolerance = 1e-5;
  o.max_coefficients = 300;
  const Approximation<2> a = approximate(d, o);
  EXPECT_FALSE(a.converged);
  EXPECT_EQ(a.stop_reason, "coefficient limit");
  EXPECT_LE(a.spline.num_basis(), 300);
}

TEST(LrApproximation, BadOptionsAndData) {
  ScatteredData<2> d = sample<2>(100, 1, 12, [](const Param<2>& p, double* v, auto&) { v[0] = p[0]; });
  ApproximationOptions o;
  EXPECT_THROW(approximate(d, o), Error);  // no tolerance
  o.tolerance = 0.1;
  o.degree = 0;
  EXPECT_THROW(approximate(d, o), Error);
  o.degree = 2;
  d.values[7] = std::nan("");
  try {
    approximate(d, o);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("point 8"), std::string::npos) << e.what();
  }
  ScatteredData<2> line = sample<2>(100, 1, 13, [](Param<2>& p, double* v, auto&) {
    p[1] = 2 * p[0] + 1;
    v[0] = p[0];
  });
  try {
    approximate(line, o);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("on a line"), std::string::npos) << e.what();
  }
  ScatteredData<2> two = sample<2>(2, 1, 14, [](const Param<2>&, double* v, auto&) { v[0] = 0; });
  EXPECT_THROW(approximate(two, o), Error);
}

}  // namespace
}  // namespace trivar

namespace trivar {
namespace {

TEST(GraphSurface, ReproducesTheParametersExactly) {
  // Locally refined cubic height fields (four levels of randomly marked elements): their graphs' x and y are u and
  // v, their z the height, at random points to rounding. There the Greville abscissae of the split B-splines are
  // no longer the identity's coefficients (they miss u by up to 1e-4); the identity carried through refinement is.
  for (const Strategy strategy : {Strategy::structured, Strategy::fullspan}) {
    SCOPED_TRACE(static_cast<int>(strategy));
    ApproximationOptions o;
    o.degree = 3;
    o.tolerance = 1.0;
    LRSpline<2> space = initial_space<2>(Box<2>{{-2, 1}, {3, 2}}, o);
    std::mt19937 pick(5);
    for (int l = 0; l < 4; ++l) {
      std::vector<int> m;
      for (int e = 0; e < space.num_elements(); ++e)
        if (pick() % 4 == 0) m.push_back(e);
      refine_elements(space, std::span<const int>(m), RefineOptions{strategy});
    }
    std::vector<double> coefs(static_cast<std::size_t>(space.num_basis()));
    for (std::size_t i = 0; i < coefs.size(); ++i) coefs[i] = std::sin(1.0 + static_cast<double>(i));
    const LRSpline<2> h = with_coefficients(space, 1, coefs);
    const LRSpline<2> g = graph_surface(h, space);
    ASSERT_EQ(g.dim(), 3);
    std::mt19937 rng(21);
    std::uniform_real_distribution<double> u(-2.0, 3.0), v(1.0, 2.0);
    for (int i = 0; i < 500; ++i) {
      const Param<2> p{u(rng), v(rng)};
      double z, xyz[3];
      h.eval(p, &z);
      g.eval(p, xyz);
      EXPECT_NEAR(xyz[0], p[0], 1e-13);
      EXPECT_NEAR(xyz[1], p[1], 1e-13);
      EXPECT_NEAR(xyz[2], z, 1e-13);
    }
    EXPECT_THROW(graph_surface(g, space), Error);
    EXPECT_THROW(graph_surface(h, initial_space<2>(Box<2>{{-2, 1}, {3, 2}}, o)), Error);
  }
}

}  // namespace
}  // namespace trivar
