#include "trivar/spline/split.hpp"

#include <gtest/gtest.h>

#include "support/spline_fixtures.hpp"
#include "trivar/core/error.hpp"
#include "trivar/spline/bezier_extraction.hpp"

using namespace trivar;

namespace {

// Random parameters of `piece`'s domain; max deviation of the piece from the reference evaluation of `whole`.
template <int D>
double piece_deviation(const TensorSpline<D>& whole, const TensorSpline<D>& piece, unsigned seed) {
  double m = 0;
  std::vector<double> y(piece.dim());
  for (const auto& u : test::random_params(piece, 300, seed)) {
    const auto ref = test::reference_eval(whole, u);
    piece.eval(u, y.data());
    for (int d = 0; d < piece.dim(); ++d) m = std::max(m, std::abs(ref[d] - y[d]));
  }
  return m;
}

template <int D>
bool clamped_in(const TensorSpline<D>& s, int dir) {
  const KnotVector& kv = s.knots(dir);
  return kv.multiplicity(kv.start()) == kv.order() && kv.multiplicity(kv.end()) == kv.order() &&
         kv.knots().front() == kv.start() && kv.knots().back() == kv.end();
}

}  // namespace

TEST(Split, HalvesReproduceTheOriginal) {
  for (bool rational : {false, true})
    for (bool clamped : {true, false}) {
      const auto s = test::random_spline<3>({3, 2, 1}, {3, 4, 2}, 3, rational, 201, clamped);
      for (int dir = 0; dir < 3; ++dir) {
        const auto dom = s.domain();
        const double u = dom.lo[dir] + 0.37 * dom.extent(dir);
        const auto [left, right] = split_at(s, dir, u);
        EXPECT_EQ(left.domain().lo[dir], dom.lo[dir]);
        EXPECT_EQ(left.domain().hi[dir], u);
        EXPECT_EQ(right.domain().lo[dir], u);
        EXPECT_EQ(right.domain().hi[dir], dom.hi[dir]);
        EXPECT_TRUE(clamped_in(left, dir));
        EXPECT_TRUE(clamped_in(right, dir));
        EXPECT_LE(piece_deviation(s, left, 202), 1e-12);
        EXPECT_LE(piece_deviation(s, right, 203), 1e-12);
        // The other directions are untouched.
        for (int k = 0; k < 3; ++k) {
          if (k != dir) {
            EXPECT_EQ(left.knots(k), s.knots(k));
          }
        }
      }
    }
}

TEST(Split, AtExistingKnotAndSnapping) {
  const auto s = test::random_spline<2>({3, 2}, {4, 3}, 2, true, 204);
  // The doubled interior knot of direction 0 (random_knots doubles the middle one for p >= 2).
  const double t = s.knots(0).breakpoints()[2];
  const auto [a, b] = split_at(s, 0, t);
  // Each interior knot below/above t stays; t gets full multiplicity in both.
  EXPECT_EQ(a.count(0) + b.count(0), s.count(0) + (s.degree(0) + 1 - s.knots(0).multiplicity(t)));
  EXPECT_LE(piece_deviation(s, a, 205), 1e-12);
  EXPECT_LE(piece_deviation(s, b, 206), 1e-12);
  // A cut a rounding error away from the knot is the knot: no sliver element.
  const auto [c, d] = split_at(s, 0, t + 1e-15);
  EXPECT_EQ(c.knots(0), a.knots(0));
  EXPECT_EQ(d.knots(0), b.knots(0));
}

TEST(Split, RejectsCutsAtOrOutsideTheEnds) {
  const auto s = test::random_spline<2>({2, 2}, {3, 3}, 3, false, 207);
  EXPECT_THROW(split_at(s, 0, 0.0), Error);
  EXPECT_THROW(split_at(s, 0, 1.0), Error);
  EXPECT_THROW(split_at(s, 1, 2.5), Error);
  EXPECT_THROW(split_at(s, 1, -1.0), Error);
  EXPECT_THROW(split_at(s, 2, 0.5), Error);
}

TEST(SubPatch, ReproducesTheOriginalOnTheBox) {
  for (bool rational : {false, true})
    for (bool clamped : {true, false}) {
      const auto s = test::random_spline<3>({2, 3, 2}, {3, 3, 4}, 3, rational, 208, clamped);
      Box<3> box;
      box.lo = {0.13, 0.55, 1.2};
      box.hi = {0.71, 1.9, 3.0};  // the end of direction 2's domain [0, 3]
      const auto p = sub_patch(s, box);
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(p.domain().lo[k], box.lo[k]);
        EXPECT_EQ(p.domain().hi[k], box.hi[k]);
        EXPECT_TRUE(clamped_in(p, k));
      }
      EXPECT_LE(piece_deviation(s, p, 209), 1e-12);
    }
}

TEST(SubPatch, WholeDomainOfClampedSplineIsIdentity) {
  const auto s = test::random_spline<2>({3, 2}, {3, 2}, 3, true, 210);
  const auto p = sub_patch(s, s.domain());
  ASSERT_EQ(p.coefs().size(), s.coefs().size());
  for (std::size_t i = 0; i < s.coefs().size(); ++i) EXPECT_EQ(p.coefs()[i], s.coefs()[i]);
}

TEST(SubPatch, RejectsBoxesOutsideOrEmpty) {
  const auto s = test::random_spline<2>({2, 2}, {3, 3}, 3, false, 211);
  Box<2> b;
  b.lo = {0.2, 0.5};
  b.hi = {1.2, 1.0};
  EXPECT_THROW(sub_patch(s, b), Error);
  b.hi = {0.2, 1.0};
  EXPECT_THROW(sub_patch(s, b), Error);
}

TEST(SplitBezierNet, DeCasteljauHalvesMatchTheNet) {
  for (bool rational : {false, true}) {
    // A single Bezier element (one interval per direction).
    const auto s = test::random_spline<3>({3, 2, 1}, {1, 1, 1}, 3, rational, 212);
    const auto el = bezier_elements(s).front();
    for (int dir = 0; dir < 3; ++dir) {
      const double t = 0.3;
      BezierElement<3> left = el, right = el;
      split_bezier_net<3>(el.degrees, el.stride(), el.coefs.data(), dir, t, left.coefs.data(), right.coefs.data());
      const double mid = el.domain.lo[dir] + t * el.domain.extent(dir);
      left.domain.hi[dir] = mid;
      right.domain.lo[dir] = mid;
      double m = 0;
      std::vector<double> a(3);
      for (const auto* piece : {&left, &right}) {
        std::mt19937 rng(213);
        for (int i = 0; i < 200; ++i) {
          Param<3> u;
          for (int k = 0; k < 3; ++k)
            u[k] = std::uniform_real_distribution<double>(piece->domain.lo[k], piece->domain.hi[k])(rng);
          eval_bezier(*piece, u, a.data());
          const auto ref = test::reference_eval(s, u);
          for (int d = 0; d < 3; ++d) m = std::max(m, std::abs(a[d] - ref[d]));
        }
      }
      EXPECT_LE(m, 1e-12) << "direction " << dir;
    }
  }
}
