// Multilevel B-spline approximation on LR B-splines: one pass against the formula of Lee, Wolberg and Shin with the
// B-spline values from the textbook recursion on each B-spline's local knots (not the fit's Bezier extraction), and
// the adaptive loop with --method mba: the tolerance met at every point by the spline's own evaluator, the carried
// residuals equal to f - s, local refinement, volumes.
#include <random>

#include "trivar/core/error.hpp"
#include "trivar/fit/lr_approximation.hpp"
#include "trivar/fit/mba.hpp"
#include "trivar/lr/refinement.hpp"
#include "fit/crater.hpp"

namespace trivar::mba_test {
namespace {

// Cox-de Boor on one local knot vector t (p + 2 knots), half-open spans.
double local_bspline(const std::vector<double>& t, std::size_t first, int p, double x) {
  if (p == 0) return t[first] <= x && x < t[first + 1] ? 1.0 : 0.0;
  double v = 0.0;
  const double a = t[first + static_cast<std::size_t>(p)] - t[first], b = t[first + static_cast<std::size_t>(p) + 1] - t[first + 1];
  if (a > 0) v += (x - t[first]) / a * local_bspline(t, first, p - 1, x);
  if (b > 0) v += (t[first + static_cast<std::size_t>(p) + 1] - x) / b * local_bspline(t, first + 1, p - 1, x);
  return v;
}

template <int D>
double scaled_value(const LRBSpline<D>& b, const Param<D>& x) {
  double v = b.gamma;
  for (int k = 0; k < D; ++k) v *= local_bspline(b.knots[k], 0, static_cast<int>(b.knots[k].size()) - 2, x[k]);
  return v;
}

using test::crater;
using test::kCx;
using test::kCy;
using test::kR;

template <int D, class F>
ScatteredData<D> sample(std::size_t n, std::uint32_t seed, F&& f) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  ScatteredData<D> d;
  d.params.resize(n);
  d.values.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k < D; ++k) d.params[i][k] = u(rng);
    d.values[i] = f(d.params[i]);
  }
  return d;
}

template <int D>
std::vector<double> evaluator_errors(const LRSpline<D>& s, const ScatteredData<D>& d) {
  std::vector<double> v(d.size());
  s.eval_many(d.params, v, 1);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = std::abs(v[i] - d.values[i]);
  return v;
}

TEST(Mba, OnePassIsTheWeightedMeanOfThePointsWishes) {
  ApproximationOptions o;
  o.initial_elements = 3;
  LRSpline<2> space = initial_space<2>(Box<2>{{0, 0}, {1, 1}}, o);
  refine_elements(space, std::span<const int>(std::vector<int>{0, 4}), RefineOptions{Strategy::minspan});
  refine_elements(space, std::span<const int>(std::vector<int>{1}), RefineOptions{});
  ASSERT_TRUE(std::any_of(space.basis_functions().begin(), space.basis_functions().end(),
                          [](const LRBSpline<2>& b) { return b.gamma < 1.0; }));  // scaled B-splines take part
  // Two components, 300 points (every B-spline holds some), coefficients and residuals at random.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0), c(-1.0, 1.0);
  ScatteredData<2> d;
  d.dim = 2;
  for (int i = 0; i < 300; ++i) {
    d.params.push_back({u(rng), u(rng)});
    d.values.push_back(c(rng));
    d.values.push_back(c(rng));
  }
  const int n = space.num_basis();
  std::vector<double> coefs(static_cast<std::size_t>(n) * 2);
  for (double& x : coefs) x = c(rng);
  const LRSpline<2> before = with_coefficients(space, 2, coefs);
  std::vector<double> residuals(600);
  for (std::size_t i = 0; i < 300; ++i) {
    double s[2];
    before.eval(d.params[i], s);
    for (int k = 0; k < 2; ++k) residuals[i * 2 + k] = d.values[i * 2 + k] - s[k];
  }
  // The formula, B-spline by B-spline.
  std::vector<double> expected = coefs;
  const auto basis = space.basis_functions();
  for (int j = 0; j < n; ++j) {
    double num[2] = {0, 0}, den = 0;
    for (std::size_t i = 0; i < 300; ++i) {
      const double w = scaled_value(basis[static_cast<std::size_t>(j)], d.params[i]);
      if (w == 0.0) continue;
      double sum2 = 0;
      for (const LRBSpline<2>& b : basis) sum2 += std::pow(scaled_value(b, d.params[i]), 2);
      for (int k = 0; k < 2; ++k) num[k] += w * w * (w * residuals[i * 2 + k] / sum2);
      den += w * w;
    }
    ASSERT_GT(den, 0.0) << j;
    for (int k = 0; k < 2; ++k) expected[static_cast<std::size_t>(j) * 2 + k] += num[k] / den;
  }
  const PointsByElement where = locate_points(space, std::span<const Param<2>>(d.params));
  mba_update(space, d, where, std::span<double>(coefs), std::span<double>(residuals));
  for (std::size_t j = 0; j < coefs.size(); ++j) EXPECT_NEAR(coefs[j], expected[j], 1e-13) << j;
  // The carried residuals are f - s of the updated spline.
  const LRSpline<2> after = with_coefficients(space, 2, coefs);
  for (std::size_t i = 0; i < 300; ++i) {
    double s[2];
    after.eval(d.params[i], s);
    for (int k = 0; k < 2; ++k) EXPECT_NEAR(residuals[i * 2 + k], d.values[i * 2 + k] - s[k], 1e-13);
  }
  // Three passes in one call (extraction operators built once) equal three calls of one pass, bit for bit, and
  // each pass brings the residual down.
  std::vector<double> c3 = coefs, r3 = residuals, c1 = coefs, r1 = residuals;
  mba_update(space, d, where, std::span<double>(c3), std::span<double>(r3), 3);
  double last = 0.0;
  for (double r : r1) last += r * r;
  for (int pass = 0; pass < 3; ++pass) {
    mba_update(space, d, where, std::span<double>(c1), std::span<double>(r1));
    double now = 0.0;
    for (double r : r1) now += r * r;
    EXPECT_LT(now, last) << pass;
    last = now;
  }
  EXPECT_EQ(c3, c1);
  EXPECT_EQ(r3, r1);
}

TEST(Mba, CraterMeetsTheToleranceWithLocalRefinement) {
  ScatteredData<2> d = sample<2>(10000, 2, [](const Param<2>& p) { return crater(p[0], p[1]); });
  for (int k = 0; k < 4; ++k) {  // the corners, so the initial elements are 1/16 wide
    d.params[static_cast<std::size_t>(k)] = {double(k & 1), double(k >> 1)};
    d.values[static_cast<std::size_t>(k)] = crater(k & 1, k >> 1);
  }
  ApproximationOptions o;
  o.method = FitMethod::mba;
  o.tolerance = 0.005 * 0.33;
  o.initial_elements = 16;
  o.max_levels = 16;
  const Approximation<2> a = approximate(d, o);
  EXPECT_TRUE(a.converged) << a.stop_reason;
  EXPECT_LT(a.spline.num_basis(), 2400);  // least squares on the 15000 points of lr_approximation_test: 1784
  const std::vector<double> e = evaluator_errors(a.spline, d);
  double worst = 0.0, diff = 0.0;
  for (std::size_t i = 0; i < e.size(); ++i) {
    worst = std::max(worst, e[i]);
    diff = std::max(diff, std::abs(e[i] - a.errors[i]));
  }
  EXPECT_LE(worst, o.tolerance);
  EXPECT_LT(diff, 1e-12);  // the residuals carried through the levels are the spline's
  EXPECT_NEAR(a.iterations.back().max_error, worst, 1e-12);
  // The refinement stays near the rim, as least squares' does (lr_approximation_test).
  int far = 0;
  double reach = 0.0;
  for (const Box<2>& el : a.spline.elements()) {
    const double dx = std::max({kCx - el.hi[0], el.lo[0] - kCx, 0.0}), dy = std::max({kCy - el.hi[1], el.lo[1] - kCy, 0.0});
    const bool refined = el.hi[0] - el.lo[0] < 0.0625 - 1e-12 || el.hi[1] - el.lo[1] < 0.0625 - 1e-12;
    if (refined) reach = std::max(reach, std::hypot(dx, dy) - kR);
    else ++far;
  }
  EXPECT_LT(reach, 0.35);
  EXPECT_GT(far, 100);
  std::printf("MBA: %d coefficients, %zu levels, refinement reaches %.3f beyond the rim, %d coarse elements\n",
              a.spline.num_basis(), a.iterations.size() - 1, reach, far);
}

TEST(Mba, VolumetricFieldAndUniformRefinement) {
  const auto f = [](const Param<3>& p) { return std::sin(3 * p[0]) * std::cos(2 * p[1]) + p[2] * p[2]; };
  const ScatteredData<3> d = sample<3>(3000, 4, f);
  ApproximationOptions o;
  o.method = FitMethod::mba;
  o.tolerance = 0.005;
  o.initial_elements = 2;
  o.max_levels = 8;
  for (bool uniform : {false, true}) {
    o.uniform = uniform;
    const Approximation<3> a = approximate(d, o);
    EXPECT_TRUE(a.converged) << a.stop_reason;
    const std::vector<double> e = evaluator_errors(a.spline, d);
    EXPECT_LE(*std::max_element(e.begin(), e.end()), o.tolerance);
    // The residuals carried through the rounds are the returned spline's: each refinement kept the function.
    for (std::size_t i = 0; i < e.size(); ++i) ASSERT_NEAR(e[i], a.errors[i], 1e-12) << i;
    EXPECT_GE(a.iterations.size(), 3u);
    if (uniform) {  // every element halved each round: a tensor spline, 2^level elements a side
      const int side = 2 << (a.iterations.size() - 1);
      EXPECT_EQ(a.spline.num_elements(), side * side * side);
    }
  }
}

TEST(Mba, MethodWords) {
  EXPECT_EQ(parse_fit_method("mba"), FitMethod::mba);
  EXPECT_EQ(parse_fit_method("ls"), FitMethod::least_squares);
  EXPECT_STREQ(to_string(FitMethod::mba), "mba");
  EXPECT_THROW(parse_fit_method("kriging"), Error);
}

}  // namespace
}  // namespace trivar::mba_test
