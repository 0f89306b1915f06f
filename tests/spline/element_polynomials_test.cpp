// The per-element power forms of a volume reproduce the spline (against the Cox-de Boor recursion, not the
// library's kernels) on every supported degree pair, rational or not, uniform and non-uniform knots with a
// doubled knot, at random points, on the element boundaries and one ulp either side, and clamp like eval().
#include "trivar/spline/element_polynomials.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "support/spline_fixtures.hpp"
#include "trivar/spline/degree_elevation.hpp"
#include "trivar/spline/simd_level.hpp"

using namespace trivar;

namespace {

// Control values are O(1): the power form in local coordinates loses two to three digits to the B-spline form
// at degree 4 (its coefficients exceed the control values by the binomial factors of the basis conversion).
constexpr double kTolerance = 1e-12;

// Points: random, the breakpoints of every direction (and an ulp either side) combined with random others.
std::vector<Param<3>> probe_points(const TensorSpline<3>& s) {
  auto u = test::random_params(s, 40, 3);
  const auto r = test::random_params(s, 64, 9);
  std::size_t q = 0;
  for (int k = 0; k < 3; ++k)
    for (double b : s.knots(k).breakpoints())
      for (double v : {std::nextafter(b, -1e300), b, std::nextafter(b, 1e300)}) {
        Param<3> p = r[q++ % r.size()];
        p[k] = std::clamp(v, s.knots(k).start(), s.knots(k).end());
        u.push_back(p);
      }
  return u;
}

void expect_reproduces(const TensorSpline<3>& s, const std::string& name) {
  const auto points = probe_points(s);
  std::vector<std::vector<double>> refs;
  for (const Param<3>& u : points) refs.push_back(test::reference_eval(s, u));
  for (SimdLevel level : {SimdLevel::generic, supported_simd_level()}) {
    limit_simd_level(level);
    const ElementPolynomials e(s);
    ASSERT_TRUE(e.available()) << name;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Param<3>& u = points[i];
      const auto& ref = refs[i];
      double x[3];
      e.eval(u, x);
      for (int d = 0; d < s.dim(); ++d)
        ASSERT_NEAR(x[d], ref[d], kTolerance * (1.0 + std::abs(ref[d])))
            << name << " " << simd_level_name(level) << " at (" << u[0] << ", " << u[1] << ", " << u[2] << ")";
      // First derivatives against the B-spline derivative kernels (checked against finite differences in
      // tensor_spline_test), scaled by the parameter lengths the local coordinates divide by.
      double f[12], g[12];
      e.eval_first(u, f);
      s.eval_derivs(u, 1, g);
      for (int d = 0; d < s.dim(); ++d) ASSERT_EQ(f[d], x[d]) << name;
      for (int q = s.dim(); q < 4 * s.dim(); ++q)
        ASSERT_NEAR(f[q], g[q], 10 * kTolerance * (1.0 + std::abs(g[q]))) << name << " derivative entry " << q;
    }
    // Outside the domain: the value at the clamped parameter, as TensorSpline::eval gives it.
    const Box<3> dom = s.domain();
    const Param<3> out{dom.lo[0] - 1.0, dom.hi[1] + 0.5, 0.5 * (dom.lo[2] + dom.hi[2])};
    const Param<3> in{dom.lo[0], dom.hi[1], out[2]};
    double a[3], b[3];
    e.eval(out, a);
    e.eval(in, b);
    for (int d = 0; d < s.dim(); ++d) EXPECT_EQ(a[d], b[d]) << name;
  }
  limit_simd_level(supported_simd_level());
}

TEST(ElementPolynomials, ReproduceTheSplineOnEverySupportedDegreeTriple) {
  for (int p = 1; p <= 4; ++p)
    for (int p1 = 1; p1 <= 4; ++p1)
      for (int q = 1; q <= 4; ++q)
        for (bool rational : {false, true}) {
          // Pairs without their own kernel (raised to the larger degree) with one last degree only.
          if (p1 != 1 && p1 != p && q != 2) continue;
          const std::string name = "degree " + std::to_string(p) + " x " + std::to_string(p1) + " x " +
                                   std::to_string(q) + (rational ? " rational" : "");
          const auto s = test::random_spline<3>({p, p1, q}, {3, 2, 2}, 3, rational, 7u * p + q);
          expect_reproduces(s, name);
          // Random control values have every power: nothing is reduced.
          const int first = std::max(p, p1 == 1 ? 1 : p1), second = p1 == 1 ? 1 : std::max(p, p1);
          EXPECT_EQ(ElementPolynomials(s).degrees(), (std::array<int, 3>{first, second, q})) << name;
        }
}

TEST(ElementPolynomials, UniformKnotsAndFewerCoordinates) {
  // Open uniform knots take the span from one multiplication; a scalar field (dim 1) leaves lanes empty.
  std::array<KnotVector, 3> kv{KnotVector::open_uniform(3, 5, -1.0, 2.0), KnotVector::open_uniform(3, 4, 0.0, 1.0),
                               KnotVector::open_uniform(2, 3, 0.5, 4.0)};
  ASSERT_GT(kv[0].uniform_inverse_spacing(), 0.0);
  for (int dim : {1, 2, 3})
    for (bool rational : {false, true}) {
      std::size_t n = static_cast<std::size_t>(kv[0].size() * kv[1].size() * kv[2].size());
      std::vector<double> pts(n * dim), w;
      std::mt19937 rng(17u * dim);
      std::uniform_real_distribution<double> X(-3.0, 3.0), W(0.5, 2.0);
      for (double& x : pts) x = X(rng);
      if (rational)
        for (std::size_t i = 0; i < n; ++i) w.push_back(W(rng));
      expect_reproduces(TensorSpline<3>::from_cartesian(kv, dim, pts, w),
                        "uniform dim " + std::to_string(dim) + (rational ? " rational" : ""));
    }
}

TEST(ElementPolynomials, ExactDegreeReduction) {
  // A trilinear map (a twisted box, rational with equal weights) raised to degree 4 x 4 x 3 by knot-free degree
  // elevation of its control net: evaluated at degree 1 in every direction, still the same map.
  std::array<KnotVector, 3> kv{KnotVector::open_uniform(1, 2, 0.0, 1.0), KnotVector::open_uniform(1, 1, 0.0, 2.0),
                               KnotVector::open_uniform(1, 1, -1.0, 1.0)};
  std::vector<double> pts;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i)
        pts.insert(pts.end(), {3.0 * i + 0.5 * j * k, 2.0 * j + 0.25 * i * k, 5.0 * k - 0.5 * i * j});
  const auto trilinear = TensorSpline<3>::from_cartesian(kv, 3, pts, std::vector<double>(12, 2.0));
  const auto raised = elevate_degree(trilinear, {3, 3, 2});
  ASSERT_EQ(raised.degree(0), 4);
  const ElementPolynomials e(raised);
  ASSERT_TRUE(e.available());
  EXPECT_EQ(e.degrees(), (std::array<int, 3>{1, 1, 1}));
  expect_reproduces(raised, "trilinear raised to 4 x 4 x 3");
  // One control point moved off the trilinear map: every degree is needed again.
  std::vector<double> c(raised.coefs().begin(), raised.coefs().end());
  c[4 * 7] += 0.1;
  const TensorSpline<3> bent(raised.knot_vectors(), 3, true, c);
  EXPECT_EQ(ElementPolynomials(bent).degrees(), (std::array<int, 3>{4, 4, 3}));
  expect_reproduces(bent, "bent");
}

TEST(ElementPolynomials, UnsupportedSplinesAreNotAvailable) {
  EXPECT_FALSE(ElementPolynomials(test::random_spline<3>({5, 5, 5}, {1, 1, 1}, 3, false, 1)).available());
  EXPECT_FALSE(ElementPolynomials(test::random_spline<3>({2, 2, 2}, {1, 1, 1}, 4, false, 1)).available());
  // 3 x 3 x 3 trilinear elements of 4 * 8 doubles, twice while the degrees are reduced: over a cap of 26
  // elements, within one of 27.
  const auto s = test::random_spline<3>({1, 1, 1}, {3, 3, 3}, 3, false, 1);
  EXPECT_FALSE(ElementPolynomials(s, 2 * 26 * 4 * 8 * sizeof(double)).available());
  EXPECT_TRUE(ElementPolynomials(s, 2 * 27 * 4 * 8 * sizeof(double)).available());
  EXPECT_FALSE(ElementPolynomials().available());
}

}  // namespace
