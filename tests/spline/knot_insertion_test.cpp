#include "trivar/spline/knot_insertion.hpp"

#include <gtest/gtest.h>

#include "support/spline_fixtures.hpp"
#include "trivar/core/error.hpp"
#include "trivar/spline/degree_elevation.hpp"

using namespace trivar;

TEST(KnotInsertion, SingleAndMultipleInsertionKeepGeometry) {
  for (bool rational : {false, true}) {
    const auto s = test::random_spline<3>({3, 2, 1}, {3, 4, 2}, 3, rational, 101);
    const auto params = test::random_params(s, 1000, 102);
    const auto a = insert_knot(s, 0, 0.37, 1);
    EXPECT_EQ(a.count(0), s.count(0) + 1);
    EXPECT_LE(test::max_deviation(s, a, params), 1e-12);
    const auto b = insert_knot(s, 1, 1.11, 2);
    EXPECT_EQ(b.count(1), s.count(1) + 2);
    EXPECT_LE(test::max_deviation(s, b, params), 1e-12);
    // Full multiplicity at an existing knot: the spline becomes C^-1 there but is unchanged.
    const double existing = s.knots(2).breakpoints()[1];
    const auto c = insert_knot(s, 2, existing, s.degree(2) + 1 - s.knots(2).multiplicity(existing));
    EXPECT_LE(test::max_deviation(s, c, params), 1e-12);
  }
}

TEST(KnotInsertion, BoehmMatchesHandComputedExample) {
  // Quadratic curve with knots {0,0,0,1,1,1} (a Bezier curve) and control points 0, 1, 0: inserting 0.5
  // gives the de Casteljau halves: 0, 0.5, 0.5, 0.
  const SplineCurve c({KnotVector(2, {0, 0, 0, 1, 1, 1})}, 1, false, {0, 1, 0});
  const auto r = insert_knot(c, 0, 0.5);
  const std::vector<double> expected{0, 0.5, 0.5, 0};
  ASSERT_EQ(r.num_coefs(), 4);
  for (int i = 0; i < 4; ++i) EXPECT_DOUBLE_EQ(r.coef(i)[0], expected[i]);
}

TEST(KnotInsertion, RefinementOfUnclampedSplines) {
  const auto s = test::random_spline<2>({3, 2}, {4, 3}, 2, true, 103, false);
  const auto r = refine_uniform(s, Ints<2>{3, 2});
  EXPECT_EQ(r.knots(0).num_elements(), 12);
  EXPECT_EQ(r.knots(1).num_elements(), 6);
  EXPECT_LE(test::max_deviation(s, r, test::random_params(s, 1000, 104)), 1e-12);
}

TEST(KnotInsertion, UniformRefinementCountsAndGeometry) {
  const auto s = test::random_spline<3>({2, 3, 2}, {2, 2, 3}, 3, false, 105);
  const auto r = refine_uniform(s, Ints<3>{2, 2, 2});
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(r.knots(k).num_elements(), 2 * s.knots(k).num_elements());
    // Each new knot is simple: count grows by the number of elements.
    EXPECT_EQ(r.count(k), s.count(k) + s.knots(k).num_elements());
  }
  EXPECT_LE(test::max_deviation(s, r, test::random_params(s, 1000, 106)), 1e-12);
}

TEST(KnotInsertion, RejectsBadKnots) {
  const auto s = test::random_spline<1>({2}, {3}, 1, false, 107);
  EXPECT_THROW(insert_knot(s, 0, 5.0), Error);
  EXPECT_THROW(insert_knot(s, 0, 0.5, 4), Error);  // multiplicity would exceed p + 1
  EXPECT_THROW(insert_knot(s, 1, 0.5), Error);
}

TEST(DegreeElevation, KeepsGeometryAndContinuity) {
  for (bool rational : {false, true})
    for (bool clamped : {true, false}) {
      const auto s = test::random_spline<3>({1, 2, 3}, {3, 3, 2}, 3, rational, 111, clamped);
      const auto e = elevate_degree(s, Ints<3>{2, 1, 1});
      EXPECT_EQ(e.degree(0), 3);
      EXPECT_EQ(e.degree(1), 3);
      EXPECT_EQ(e.degree(2), 4);
      for (int k = 0; k < 3; ++k) {
        // Every distinct knot gains one multiplicity per degree.
        const auto m0 = s.knots(k).multiplicities(), m1 = e.knots(k).multiplicities();
        ASSERT_EQ(m0.size(), m1.size());
        for (std::size_t i = 0; i < m0.size(); ++i) EXPECT_EQ(m1[i], m0[i] + e.degree(k) - s.degree(k));
      }
      EXPECT_LE(test::max_deviation(s, e, test::random_params(s, 1000, 112)), 1e-12);
    }
}

TEST(DegreeElevation, LineBecomesEquallySpacedQuadratic) {
  // A straight line from 0 to 1 elevated to degree 2 has control points 0, 0.5, 1 (linear precision).
  const SplineCurve c({KnotVector(1, {0, 0, 1, 1})}, 1, false, {0, 1});
  const auto e = elevate_degree(c, 0, 1);
  ASSERT_EQ(e.num_coefs(), 3);
  EXPECT_NEAR(e.coef(0)[0], 0.0, 1e-15);
  EXPECT_NEAR(e.coef(1)[0], 0.5, 1e-15);
  EXPECT_NEAR(e.coef(2)[0], 1.0, 1e-15);
}
