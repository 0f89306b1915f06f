#include "trivar/spline/point_inversion.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "support/spline_fixtures.hpp"
#include "trivar/core/error.hpp"
#include "trivar/core/parallel.hpp"
#include "trivar/spline/degree_elevation.hpp"
#include "trivar/spline/knot_insertion.hpp"

using namespace trivar;

namespace {

const double kInvSqrt2 = std::sqrt(0.5);

// Exact quarter annulus r in [1, 2], theta in [0, pi/2] (rational quadratic arcs), extruded over z in [0, 1]
// when D = 3; then elevated to cubic and refined so it has several curved rational elements.
template <int D>
TensorSpline<D> quarter_annulus() {
  std::array<KnotVector, D> kv;
  kv[0] = KnotVector(1, {0, 0, 1, 1});
  kv[1] = KnotVector(2, {0, 0, 0, 1, 1, 1});
  if constexpr (D == 3) kv[2] = KnotVector(1, {0, 0, 1, 1});
  const double arc[3][2] = {{1, 0}, {1, 1}, {0, 1}};
  const double warc[3] = {1, kInvSqrt2, 1};
  std::vector<double> pts, w;
  for (int k = 0; k < (D == 3 ? 2 : 1); ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 2; ++i) {
        const double rho = 1.0 + i;
        pts.push_back(rho * arc[j][0]);
        pts.push_back(rho * arc[j][1]);
        if constexpr (D == 3) pts.push_back(k);
        w.push_back(warc[j]);
      }
  auto s = TensorSpline<D>::from_cartesian(kv, D, pts, w);
  Ints<D> by, parts;
  by.fill(1);
  parts.fill(2);
  by[0] = 2;
  parts[1] = 3;
  return refine_uniform(elevate_degree(s, by), parts);
}

// Tricubic curved box: Greville points of non-uniform knots mapped by a smooth near-identity deformation with
// positive Jacobian; rational with random weights when asked.
TensorSpline<3> curved_box(bool rational, unsigned seed) {
  std::mt19937 rng(seed);
  std::array<KnotVector, 3> kv;
  for (int k = 0; k < 3; ++k) kv[k] = test::random_knots(3, 3, rng);
  std::array<std::vector<double>, 3> g;
  for (int k = 0; k < 3; ++k) g[k] = kv[k].greville();
  std::vector<double> pts, w;
  std::uniform_real_distribution<double> W(0.8, 1.25);
  const double pi = std::numbers::pi;
  for (double c : g[2])
    for (double b : g[1])
      for (double a : g[0]) {
        pts.push_back(a + 0.15 * std::sin(pi * b));
        pts.push_back(b + 0.15 * std::sin(pi * c));
        pts.push_back(c + 0.1 * std::sin(pi * a));
        w.push_back(rational ? W(rng) : 1.0);
      }
  if (!rational) w.clear();
  return SplineVolume::from_cartesian(kv, 3, pts, w);
}

template <int D>
double param_error(const Param<D>& a, const Param<D>& b) {
  double m = 0;
  for (int k = 0; k < D; ++k) m = std::max(m, std::abs(a[k] - b[k]));
  return m;
}

// Round trip u -> x = s(u) -> invert(x) with and without a guess.
template <int D>
void check_round_trip(const TensorSpline<D>& s, unsigned seed) {
  InversionOptions opts;
  opts.tolerance = 1e-12;
  const PointInverter<D> inv(s, opts);
  std::mt19937 rng(seed);
  std::normal_distribution<double> N(0.0, 0.03);
  int fallbacks = 0;
  for (const auto& u : test::random_params(s, 300, seed)) {
    const auto x = test::reference_eval(s, u);
    const auto r = inv.invert(x.data());
    ASSERT_TRUE(r.found);
    ASSERT_TRUE(r.converged);
    EXPECT_TRUE(r.used_fallback);
    EXPECT_LE(r.residual, inv.absolute_tolerance());
    EXPECT_LE(param_error<D>(r.param, u), 1e-10);
    Param<D> guess = u;
    for (auto& g : guess) g += N(rng);
    const auto rg = inv.invert(x.data(), guess);
    ASSERT_TRUE(rg.converged);
    fallbacks += rg.used_fallback;
    EXPECT_LE(param_error<D>(rg.param, u), 1e-10);
    // From the far corner of the domain: Newton or the fallback, the answer is the same.
    const auto rf = inv.invert(x.data(), s.domain().hi);
    ASSERT_TRUE(rf.converged);
    EXPECT_LE(param_error<D>(rf.param, u), 1e-10);
  }
  // A nearby guess converges by Newton alone.
  EXPECT_LE(fallbacks, 3);
}

}  // namespace

TEST(PointInversion, CurvedTricubicBoxRoundTrip) {
  check_round_trip(curved_box(false, 601), 602);
  check_round_trip(curved_box(true, 603), 604);
}

TEST(PointInversion, QuarterAnnulusVolumeRoundTrip) { check_round_trip(quarter_annulus<3>(), 605); }

TEST(PointInversion, AnalyticPointsOfTheAnnulusAreFound) {
  const auto s = quarter_annulus<3>();
  const PointInverter<3> inv(s);
  std::mt19937 rng(606);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (int i = 0; i < 300; ++i) {
    // Include the boundary: r = 1, 2; theta = 0, pi/2; z = 0, 1.
    const double r = i % 7 == 0 ? 1.0 : (i % 7 == 1 ? 2.0 : 1.0 + U(rng));
    const double t = i % 5 == 0 ? 0.0 : (i % 5 == 1 ? std::numbers::pi / 2 : U(rng) * std::numbers::pi / 2);
    const double z = i % 3 == 0 ? 0.0 : (i % 3 == 1 ? 1.0 : U(rng));
    const double x[3] = {r * std::cos(t), r * std::sin(t), z};
    const auto res = inv.invert(x);
    ASSERT_TRUE(res.found && res.converged) << r << " " << t << " " << z;
    const auto y = test::reference_eval(s, res.param);
    EXPECT_LE(std::hypot(y[0] - x[0], y[1] - x[1], y[2] - x[2]), inv.absolute_tolerance() * 1.0001);
  }
}

TEST(PointInversion, PointsOutsideAreNotFound) {
  const auto s = quarter_annulus<3>();
  const PointInverter<3> inv(s);
  const double pi = std::numbers::pi;
  struct Cyl {
    double r, t, z;
  };
  // Just outside every face, and points inside the control hull but outside the image (corner region).
  for (const Cyl c : {Cyl{0.97, 0.7, 0.5}, Cyl{2.03, 0.3, 0.5}, Cyl{1.5, -0.02, 0.5}, Cyl{1.5, pi / 2 + 0.02, 0.5},
                      Cyl{1.5, 0.8, -0.01}, Cyl{1.5, 0.8, 1.01}, Cyl{2.5, pi / 4, 0.5}, Cyl{2.2, pi / 4, 0.9},
                      Cyl{0.8, pi / 4, 0.2}, Cyl{10, 1, 1}}) {
    const double x[3] = {c.r * std::cos(c.t), c.r * std::sin(c.t), c.z};
    const auto r = inv.invert(x);
    EXPECT_FALSE(r.found) << c.r << " " << c.t << " " << c.z;
    EXPECT_FALSE(r.converged);
    const auto rn = inv.newton(x, Param<3>{0.5, 0.5, 0.5});
    EXPECT_FALSE(rn.converged);
    EXPECT_FALSE(invert(s, x).found);
  }
}

TEST(PointInversion, PlanarSurface) {
  const auto s = quarter_annulus<2>();
  const PointInverter<2> inv(s);
  std::mt19937 rng(607);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (int i = 0; i < 300; ++i) {
    const double r = 1.0 + U(rng), t = U(rng) * std::numbers::pi / 2;
    const double x[2] = {r * std::cos(t), r * std::sin(t)};
    const auto res = inv.invert(x);
    ASSERT_TRUE(res.found && res.converged);
    const auto y = test::reference_eval(s, res.param);
    EXPECT_LE(std::hypot(y[0] - x[0], y[1] - x[1]), inv.absolute_tolerance() * 1.0001);
    const double out[2] = {(2.0 + 0.5 * U(rng)) * std::cos(t), (2.0 + 0.5 * U(rng)) * std::sin(t)};
    EXPECT_FALSE(inv.invert(out).found);
  }
  check_round_trip(s, 608);
}

TEST(PointInversion, CurveOnALine) {
  const SplineCurve c({KnotVector(3, {0, 0, 0, 0, 0.4, 1, 1, 1, 1})}, 1, false, {0, 0.2, 0.9, 1.5, 2});
  const PointInverter<1> inv(c);
  for (int i = 0; i <= 100; ++i) {
    const double x = 2.0 * i / 100;
    const auto r = inv.invert(&x);
    ASSERT_TRUE(r.converged);
    EXPECT_NEAR(test::reference_eval(c, r.param)[0], x, inv.absolute_tolerance());
  }
  const double out = 2.01;
  EXPECT_FALSE(inv.invert(&out).found);
}

TEST(PointInversion, ConstQueriesAreThreadSafe) {
  const auto s = curved_box(true, 609);
  const PointInverter<3> inv(s);
  const auto params = test::random_params(s, 400, 610);
  std::vector<std::vector<double>> xs;
  for (const auto& u : params) xs.push_back(test::reference_eval(s, u));
  std::vector<Param<3>> seq(params.size()), par(params.size());
  for (std::size_t i = 0; i < params.size(); ++i) seq[i] = inv.invert(xs[i].data()).param;
  parallel_for(static_cast<std::ptrdiff_t>(params.size()), 2,
               [&](std::ptrdiff_t i) { par[i] = inv.invert(xs[i].data()).param; });
  for (std::size_t i = 0; i < params.size(); ++i) EXPECT_EQ(seq[i], par[i]);
}

TEST(PointInversion, RejectsMismatchedDimensionAndOptions) {
  const auto s = test::random_spline<2>({2, 2}, {2, 2}, 3, false, 611);
  EXPECT_THROW(PointInverter<2>{s}, Error);
  const auto p = quarter_annulus<2>();
  InversionOptions bad;
  bad.tolerance = 0;
  EXPECT_THROW((PointInverter<2>{p, bad}), Error);
}
