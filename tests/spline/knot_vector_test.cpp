#include "trivar/spline/knot_vector.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "trivar/core/error.hpp"

using trivar::Error;
using trivar::KnotVector;

TEST(KnotVector, RejectsInvalidInputWithClearMessages) {
  auto message = [](auto&& f) {
    try {
      f();
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message([] { KnotVector(2, {0, 0, 0, 1, 0.5, 1, 1, 1}); }).find("knot 4 (0.5) is smaller than knot 3"),
            std::string::npos);
  EXPECT_NE(message([] { KnotVector(2, {0, 0, 0, 0, 1, 1, 1}); }).find("multiplicity 4 > degree + 1 = 3"),
            std::string::npos);
  EXPECT_NE(message([] { KnotVector(3, {0, 0, 0, 1, 1, 1}); }).find("needs at least 8 knots"), std::string::npos);
  EXPECT_NE(message([] { KnotVector(1, {0, 1, 1, 2}); }).find("empty domain"), std::string::npos);
  EXPECT_NE(message([] { KnotVector(1, {0, 0, std::nan(""), 1}); }).find("not finite"), std::string::npos);
  EXPECT_NE(message([] { KnotVector(-1, {0, 1}); }).find("degree -1"), std::string::npos);
}

TEST(KnotVector, SpanSearchAtRepeatedKnotsAndEnds) {
  const KnotVector kv(2, {0, 0, 0, 1, 2, 2, 3, 4, 4, 4});
  // Span s satisfies t_s <= u < t_{s+1} with a non-empty interval.
  EXPECT_EQ(kv.find_span(0.0), 2);
  EXPECT_EQ(kv.find_span(0.5), 2);
  EXPECT_EQ(kv.find_span(1.0), 3);
  EXPECT_EQ(kv.find_span(2.0), 5);  // knot 2 is doubled: indices 4, 5
  EXPECT_EQ(kv.find_span(1.999), 3);
  EXPECT_EQ(kv.find_span(3.5), 6);
  EXPECT_EQ(kv.find_span(4.0), 6);  // right end: last non-empty span
  EXPECT_EQ(kv.find_span(5.0), 6);
  EXPECT_EQ(kv.find_span(-1.0), 2);
  for (double u = 0; u <= 4.0; u += 0.01) {
    const int s = kv.find_span(u);
    EXPECT_LT(kv[s], kv[s + 1]);
    EXPECT_LE(kv[s], u);
    if (u < 4.0) {
      EXPECT_LT(u, kv[s + 1]);
    }
  }
}

TEST(KnotVector, UnclampedSpanSkipsEmptyLeadingIntervals) {
  const KnotVector kv(2, {0, 1, 1, 1, 2, 3, 3});  // domain [t_2, t_4] = [1, 2]; t_2 == t_3
  EXPECT_EQ(kv.start(), 1.0);
  EXPECT_EQ(kv.end(), 2.0);
  EXPECT_EQ(kv.find_span(1.0), 3);
  EXPECT_EQ(kv.find_span(0.5), 3);
  EXPECT_EQ(kv.find_span(2.0), 3);
}

TEST(KnotVector, MultiplicitiesBreakpointsGreville) {
  const KnotVector kv(3, {0, 0, 0, 0, 1, 2, 2, 3, 3, 3, 3});
  EXPECT_EQ(kv.size(), 7);
  EXPECT_EQ(kv.multiplicity(2.0), 2);
  EXPECT_EQ(kv.multiplicity(0.5), 0);
  EXPECT_EQ(kv.unique(), (std::vector<double>{0, 1, 2, 3}));
  EXPECT_EQ(kv.multiplicities(), (std::vector<int>{4, 1, 2, 4}));
  EXPECT_EQ(kv.breakpoints(), (std::vector<double>{0, 1, 2, 3}));
  EXPECT_EQ(kv.num_elements(), 3);
  EXPECT_TRUE(kv.is_clamped());
  const auto g = kv.greville();
  ASSERT_EQ(g.size(), 7u);
  EXPECT_DOUBLE_EQ(g[0], 0.0);
  EXPECT_DOUBLE_EQ(g[1], 1.0 / 3);
  EXPECT_DOUBLE_EQ(g[2], 1.0);
  EXPECT_DOUBLE_EQ(g[3], 5.0 / 3);
  EXPECT_DOUBLE_EQ(g[6], 3.0);
}

TEST(KnotVector, OpenUniform) {
  const auto kv = KnotVector::open_uniform(2, 4, 0.0, 2.0);
  EXPECT_EQ(kv.knots(), (std::vector<double>{0, 0, 0, 0.5, 1, 1.5, 2, 2, 2}));
  EXPECT_EQ(kv.size(), 6);
  EXPECT_THROW(KnotVector::open_uniform(2, 0), Error);
}

TEST(KnotVector, UniformFastSpanSearchAgreesWithBinarySearch) {
  // Uniform knots take an O(1) path; compare with the definition on many elements, at and next to knots.
  for (int p : {1, 2, 3}) {
    const auto kv = KnotVector::open_uniform(p, 1000, -1.0, 2.0);
    const auto& t = kv.knots();
    auto reference = [&](double u) {
      if (u >= kv.end()) return kv.size() - 1;
      if (u < kv.start()) return p;
      return static_cast<int>(std::upper_bound(t.begin(), t.end(), u) - t.begin()) - 1;
    };
    for (int i = 0; i <= 1000; ++i) {
      const double knot = t[p + i];
      for (double u : {knot, std::nextafter(knot, -10.0), std::nextafter(knot, 10.0)}) EXPECT_EQ(kv.find_span(u), reference(u)) << u;
    }
    EXPECT_EQ(kv.find_span(-5.0), p);
    EXPECT_EQ(kv.find_span(7.0), kv.size() - 1);
  }
}

namespace {

std::string knot_error(int degree, std::vector<double> knots) {
  try {
    KnotVector(degree, std::move(knots));
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

// Basis evaluation divides by spans; a subnormal span makes 1/h infinite and the span search index NaN.
TEST(KnotVector, RejectsSpansBelowTheKnotToleranceOfTheDomain) {
  EXPECT_EQ(knot_error(2, {0, 0, 0, 1e-320, 2e-320, 1, 1, 1}),
            "knot vector: span [t_2, t_3] = [0, 1e-320] is non-zero but shorter than 1e-12 (1e-12 of the domain "
            "length)");
  // Relative to the domain length 1000: a span of 1e-10 is below 1e-9, one of 1e-8 is accepted and found.
  EXPECT_NE(knot_error(1, {0, 0, 500, 500 + 1e-10, 1000, 1000}).find("span [t_2, t_3]"), std::string::npos);
  const KnotVector fine(1, {0, 0, 500, 500 + 1e-8, 1000, 1000});
  EXPECT_EQ(fine.find_span(500 + 0.5e-8), 2);
  EXPECT_EQ(fine.find_span(500 + 1e-8), 3);
  // A uniform vector of the smallest accepted spans on a tiny domain still has finite reciprocal spans.
  const KnotVector tiny = KnotVector::open_uniform(2, 4, 0.0, 1e-300);
  EXPECT_EQ(tiny.find_span(0.6e-300), 4);
}

TEST(KnotVector, RejectsKnotsWhoseDistanceOverflows) {
  EXPECT_EQ(knot_error(1, {-1.7e308, -1.7e308, 1.7e308, 1.7e308}),
            "knot vector: the knots span [-1.7e+308, 1.7e+308], whose length overflows a double");
  EXPECT_EQ(knot_error(1, {0, 0, 1, 1.7e308}).find("overflow"), std::string::npos);  // a finite length is fine
}
