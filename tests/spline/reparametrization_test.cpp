#include "trivar/spline/reparametrization.hpp"

#include <gtest/gtest.h>

#include "support/spline_fixtures.hpp"
#include "trivar/core/error.hpp"

using namespace trivar;

namespace {

// max over random parameters u of s of |r(map(u)) - s(u)| with s by reference evaluation.
template <int D, class Map>
double deviation(const TensorSpline<D>& s, const TensorSpline<D>& r, Map map, unsigned seed) {
  double m = 0;
  std::vector<double> y(r.dim());
  for (const auto& u : test::random_params(s, 300, seed)) {
    const auto ref = test::reference_eval(s, u);
    r.eval(map(u), y.data());
    for (int d = 0; d < r.dim(); ++d) m = std::max(m, std::abs(ref[d] - y[d]));
  }
  return m;
}

}  // namespace

TEST(Reparametrization, ReverseMirrorsTheParameter) {
  for (bool rational : {false, true})
    for (bool clamped : {true, false}) {
      const auto s = test::random_spline<3>({3, 2, 1}, {3, 4, 2}, 3, rational, 401, clamped);
      for (int dir = 0; dir < 3; ++dir) {
        const auto r = reverse(s, dir);
        const auto dom = s.domain();
        EXPECT_EQ(r.domain().lo[dir], dom.lo[dir]);
        EXPECT_EQ(r.domain().hi[dir], dom.hi[dir]);
        auto mirror = [&](Param<3> u) {
          u[dir] = dom.lo[dir] + dom.hi[dir] - u[dir];
          return u;
        };
        EXPECT_LE(deviation(s, r, mirror, 402), 1e-12);
        // Reversing twice restores the control grid exactly.
        const auto rr = reverse(r, dir);
        for (std::size_t i = 0; i < s.coefs().size(); ++i) ASSERT_EQ(rr.coefs()[i], s.coefs()[i]);
      }
    }
}

TEST(Reparametrization, SwapExchangesDirections) {
  for (bool rational : {false, true}) {
    const auto s = test::random_spline<3>({3, 2, 1}, {2, 3, 4}, 2, rational, 403);
    for (auto [a, b] : {std::pair{0, 1}, std::pair{0, 2}, std::pair{1, 2}, std::pair{2, 0}}) {
      const auto r = swap_directions(s, a, b);
      EXPECT_EQ(r.knots(a), s.knots(b));
      EXPECT_EQ(r.knots(b), s.knots(a));
      auto swap = [&](Param<3> u) {
        std::swap(u[a], u[b]);
        return u;
      };
      EXPECT_LE(deviation(s, r, swap, 404), 1e-12);
    }
  }
  const auto c = test::random_spline<2>({2, 3}, {3, 2}, 3, true, 405);
  const auto t = swap_directions(c, 0, 1);
  EXPECT_LE(deviation(c, t, [](Param<2> u) { return Param<2>{u[1], u[0]}; }, 406), 1e-12);
}

TEST(Reparametrization, AffineMapOfTheDomain) {
  for (bool clamped : {true, false}) {
    const auto s = test::random_spline<2>({3, 2}, {4, 3}, 3, true, 407, clamped);
    const auto r = reparametrize(s, 1, -2.5, 7.0);
    EXPECT_EQ(r.domain().lo[1], -2.5);
    EXPECT_EQ(r.domain().hi[1], 7.0);
    EXPECT_EQ(r.knots(0), s.knots(0));
    const auto dom = s.domain();
    auto phi = [&](Param<2> u) {
      u[1] = -2.5 + (u[1] - dom.lo[1]) / dom.extent(1) * 9.5;
      return u;
    };
    EXPECT_LE(deviation(s, r, phi, 408), 1e-12);
  }
}

TEST(Reparametrization, RejectsBadInput) {
  const auto s = test::random_spline<2>({2, 2}, {2, 2}, 2, false, 409);
  EXPECT_THROW(reverse(s, 2), Error);
  EXPECT_THROW(swap_directions(s, 0, 2), Error);
  EXPECT_THROW(reparametrize(s, 0, 1.0, 1.0), Error);
  EXPECT_THROW(reparametrize(s, 0, 2.0, 1.0), Error);
}
