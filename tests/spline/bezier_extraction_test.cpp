#include "trivar/spline/bezier_extraction.hpp"

#include <gtest/gtest.h>

#include "support/spline_fixtures.hpp"
#include "trivar/spline/basis.hpp"
#include "trivar/spline/derivative_index.hpp"

using namespace trivar;

TEST(BezierExtraction, OperatorsMapBSplinesToBernstein) {
  std::mt19937 rng(201);
  for (int p = 1; p <= 4; ++p) {
    const KnotVector kv = test::random_knots(p, 5, rng, 0.0, 2.0);
    const auto ops = extraction_operators(kv);
    ASSERT_EQ(static_cast<int>(ops.size()), kv.num_elements());
    std::vector<double> N(p + 1);
    for (const auto& e : ops) {
      for (int q = 0; q < 10; ++q) {
        const double u = e.lo + (e.hi - e.lo) * (q + 0.5) / 10, t = (u - e.lo) / (e.hi - e.lo);
        basis_values(kv.data(), p, kv.find_span(u), u, N.data());
        EXPECT_EQ(kv.find_span(u) - p, e.first);
        for (int i = 0; i <= p; ++i) {
          double v = 0;
          for (int j = 0; j <= p; ++j)
            v += e.C(i, j) * static_cast<double>(binomial(p, j)) * std::pow(t, j) * std::pow(1 - t, p - j);
          EXPECT_NEAR(v, N[i], 1e-13);
        }
      }
    }
  }
}

TEST(BezierExtraction, ElementsReproduceTheSpline) {
  for (bool rational : {false, true}) {
    const auto s = test::random_spline<3>({2, 3, 1}, {3, 2, 4}, 3, rational, 202);
    const auto elements = bezier_elements(s);
    ASSERT_EQ(elements.size(), 3u * 2u * 4u);
    std::vector<double> x(3), y(3);
    for (const auto& e : elements) {
      EXPECT_EQ(e.coefs.size(), static_cast<std::size_t>(3 * 4 * 2 * s.stride()));
      for (const auto& u : test::random_params(s, 20, 203)) {
        Param<3> v;
        for (int k = 0; k < 3; ++k) v[k] = e.domain.lo[k] + (e.domain.hi[k] - e.domain.lo[k]) * (u[k] / s.domain().hi[k]);
        s.eval(v, x.data());
        eval_bezier(e, v, y.data());
        for (int d = 0; d < 3; ++d) EXPECT_NEAR(x[d], y[d], 1e-12);
      }
    }
  }
}
