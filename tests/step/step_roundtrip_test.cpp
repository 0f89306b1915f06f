// trivar -> STEP file -> trivar for every object kind: bit-exact data for polynomial splines and LR splines,
// evaluation to 1e-14 for rational ones (STEP stores Cartesian points, trivar homogeneous ones).
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>

#include "support/spline_fixtures.hpp"
#include "trivar/io/step/step_file.hpp"

using namespace trivar;
using namespace trivar::io::step;

namespace {

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("trivar_step_geo_" + std::to_string(getpid()) + "_" + name))
      .string();
}

StepContents round_trip(const std::vector<AnySpline>& s, const std::vector<AnyLRSpline>& lr, const std::string& name) {
  const std::string path = temp_path(name);
  write_step(path, s, lr, {}, "2026-01-01T00:00:00");
  StepContents c = read_step(path);
  std::filesystem::remove(path);
  return c;
}

double scale(std::span<const double> v) {
  double m = 1.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

template <int D>
void expect_same(const TensorSpline<D>& a, const TensorSpline<D>& b, unsigned seed) {
  ASSERT_EQ(a.is_rational(), b.is_rational());
  ASSERT_EQ(a.dim(), b.dim());
  for (int k = 0; k < D; ++k) EXPECT_EQ(a.knots(k), b.knots(k));  // bit-exact knots
  if (!a.is_rational()) {
    EXPECT_TRUE(std::equal(a.coefs().begin(), a.coefs().end(), b.coefs().begin(), b.coefs().end()));
    return;
  }
  for (int i = 0; i < a.num_coefs(); ++i) EXPECT_EQ(a.weight(i), b.weight(i));  // weights bit-exact
  const double tol = 1e-14 * scale(a.coefs());
  std::vector<double> x(static_cast<std::size_t>(a.dim())), y(x.size());
  for (const auto& u : test::random_params(a, 200, seed)) {
    a.eval(u, x.data());
    b.eval(u, y.data());
    for (std::size_t d = 0; d < x.size(); ++d) EXPECT_NEAR(x[d], y[d], tol);
  }
}

template <int D>
void expect_same_lr(const LRSpline<D>& a, const LRSpline<D>& b, unsigned seed) {
  ASSERT_EQ(a.num_basis(), b.num_basis());
  ASSERT_EQ(a.is_rational(), b.is_rational());
  for (int i = 0; i < a.num_basis(); ++i) {
    const auto& p = a.basis_function(i);
    const auto& q = b.basis_function(i);
    EXPECT_EQ(p.knots, q.knots);
    EXPECT_EQ(p.gamma, q.gamma);
    if (!a.is_rational()) {
      EXPECT_EQ(p.coef, q.coef);
    } else {
      EXPECT_EQ(p.coef.back(), q.coef.back());  // the weight
    }
  }
  std::mt19937 rng(seed);
  const double tol = 1e-14 * 8;
  std::vector<double> x(static_cast<std::size_t>(a.dim())), y(x.size());
  for (int n = 0; n < 200; ++n) {
    Param<D> u;
    for (int k = 0; k < D; ++k)
      u[k] = std::uniform_real_distribution<double>(a.domain().lo[k], a.domain().hi[k])(rng);
    a.eval(u, x.data());
    b.eval(u, y.data());
    for (std::size_t d = 0; d < x.size(); ++d) EXPECT_NEAR(x[d], y[d], tol * std::max(1.0, std::abs(x[d])));
  }
}

// An LR spline with scaling factors below 1: a mesh line inserted across part of the domain.
template <int D>
LRSpline<D> refined(bool rational, unsigned seed) {
  Ints<D> p, e;
  p.fill(2);
  e.fill(4);
  const auto t = test::random_spline<D>(p, e, 3, rational, seed);
  LRSpline<D> s(t);
  std::array<std::vector<double>, D> bp;
  for (int k = 0; k < D; ++k) bp[k] = t.knots(k).breakpoints();
  // Three partial insertions (the third crosses the second's T-junctions), which leave scaling factors < 1.
  const auto insert = [&](int dir, double value, const Ints<D>& from, const Ints<D>& to) {
    Param<D> lo{}, hi{};
    for (int k = 0; k < D; ++k) {
      lo[k] = bp[k][from[k]];
      hi[k] = bp[k][to[k]];
    }
    EXPECT_TRUE(s.insert(MeshRectangle<D>::make(dir, value, lo, hi)));
  };
  Ints<D> from{}, to{};
  to.fill(3);
  insert(0, 0.5 * (bp[0][1] + bp[0][2]), from, to);
  insert(1, 0.5 * (bp[1][1] + bp[1][2]), from, to);
  from[1] = 1;
  to[1] = 4;
  insert(0, 0.5 * (bp[0][2] + bp[0][3]), from, to);
  return s;
}

}  // namespace

TEST(StepRoundTrip, TensorSplines) {
  for (bool rational : {false, true}) {
    const unsigned seed = rational ? 11u : 7u;
    const auto c = test::random_spline<1>({3}, {5}, 3, rational, seed);
    const auto s = test::random_spline<2>({2, 3}, {4, 3}, 3, rational, seed + 1);
    const auto v = test::random_spline<3>({1, 2, 3}, {3, 2, 2}, 3, rational, seed + 2);
    const auto c2 = test::random_spline<1>({2}, {3}, 2, rational, seed + 3);  // a 2-D (pcurve-like) curve
    const auto r = round_trip({c, s, v}, {}, "tensor.stp");
    ASSERT_EQ(r.splines.size(), 3u);
    expect_same(c, std::get<TensorSpline<1>>(r.splines[0]), seed);
    expect_same(s, std::get<TensorSpline<2>>(r.splines[1]), seed);
    expect_same(v, std::get<TensorSpline<3>>(r.splines[2]), seed);
    const auto r2 = round_trip({c2}, {}, "curve2d.stp");
    expect_same(c2, std::get<TensorSpline<1>>(r2.splines.at(0)), seed);
  }
}

TEST(StepRoundTrip, LRSplines) {
  for (bool rational : {false, true}) {
    const auto s = refined<2>(rational, 21);
    const auto v = refined<3>(rational, 22);
    double smallest = 1.0;
    for (const auto& b : s.basis_functions()) smallest = std::min(smallest, b.gamma);
    for (const auto& b : v.basis_functions()) smallest = std::min(smallest, b.gamma);
    EXPECT_LT(smallest, 1.0);
    const auto r = round_trip({}, {s, v}, "lr.stp");
    ASSERT_EQ(r.lr_splines.size(), 2u);
    expect_same_lr(s, std::get<LRSpline<2>>(r.lr_splines[0]), 5);
    expect_same_lr(v, std::get<LRSpline<3>>(r.lr_splines[1]), 6);
  }
}

// A surface read from STEP evaluates to the same points as the source it was written from, and the hand-made
// files survive a read -> write -> read cycle unchanged.
TEST(StepRoundTrip, HandWrittenFilesRewritten) {
  for (const char* f : {"bilinear_patch.stp", "curve_forms.stp", "volume_forms.stp", "quarter_circle.stp",
                        "cad_part_ap214.stp", "lr_surface_0based.stp", "lr_surface_rational.stp", "lr_volume.stp"}) {
    const auto a = read_step(std::string(TRIVAR_TEST_DATA) + "/step/geometry/" + f);
    const auto b = round_trip(a.splines, a.lr_splines, "rewrite.stp");
    ASSERT_EQ(a.splines.size(), b.splines.size()) << f;
    ASSERT_EQ(a.lr_splines.size(), b.lr_splines.size()) << f;
    for (std::size_t i = 0; i < a.splines.size(); ++i)
      std::visit(
          [&](const auto& x) {
            using T = std::decay_t<decltype(x)>;
            expect_same(x, std::get<T>(b.splines[i]), 3);
          },
          a.splines[i]);
    for (std::size_t i = 0; i < a.lr_splines.size(); ++i)
      std::visit(
          [&](const auto& x) {
            using T = std::decay_t<decltype(x)>;
            expect_same_lr(x, std::get<T>(b.lr_splines[i]), 4);
          },
          a.lr_splines[i]);
  }
}
