#include "trivar/spline/basis.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "support/spline_fixtures.hpp"

using namespace trivar;

TEST(Basis, MatchesCoxDeBoorAndSumsToOne) {
  std::mt19937 rng(7);
  for (int p = 0; p <= 6; ++p) {
    const KnotVector kv = test::random_knots(p, 7, rng, -1.0, 2.0);
    std::vector<double> N(p + 1);
    for (int q = 0; q <= 500; ++q) {
      const double u = -1.0 + 3.0 * q / 500;
      const int s = kv.find_span(u);
      basis_values(kv.data(), p, s, u, N.data());
      double sum = 0;
      for (int i = 0; i <= p; ++i) {
        sum += N[i];
        EXPECT_GE(N[i], -1e-15);
        EXPECT_NEAR(N[i], test::cox_de_boor(kv.knots(), s - p + i, p, u, kv.end()), 1e-13) << p << " " << u;
      }
      EXPECT_NEAR(sum, 1.0, 1e-14);
    }
  }
}

TEST(Basis, DerivativesMatchFiniteDifferencesAndSumToZero) {
  std::mt19937 rng(11);
  for (int p = 1; p <= 6; ++p) {
    const KnotVector kv = test::random_knots(p, 5, rng, 0.0, 1.0);
    const int n = 3;
    std::vector<double> ders((n + 1) * (p + 1)), lo((n + 1) * (p + 1)), hi((n + 1) * (p + 1));
    for (int q = 0; q < 200; ++q) {
      const double u = (q + 0.5) / 200;
      const int s = kv.find_span(u);
      const double h = 1e-6;
      if (kv.find_span(u - h) != s || kv.find_span(u + h) != s) continue;  // stay on one polynomial piece
      basis_derivatives(kv.data(), p, s, u, n, ders.data());
      basis_derivatives(kv.data(), p, s, u - h, n, lo.data());
      basis_derivatives(kv.data(), p, s, u + h, n, hi.data());
      for (int k = 0; k < n; ++k) {
        double sum = 0;
        for (int i = 0; i <= p; ++i) {
          const double fd = (hi[k * (p + 1) + i] - lo[k * (p + 1) + i]) / (2 * h);
          const double scale = 1.0 + std::abs(ders[(k + 1) * (p + 1) + i]);
          EXPECT_NEAR(ders[(k + 1) * (p + 1) + i], fd, 1e-5 * scale) << "p=" << p << " k=" << k + 1;
          sum += ders[(k + 1) * (p + 1) + i];
        }
        EXPECT_NEAR(sum, 0.0, 1e-8);
      }
      if (p < n) {
        for (int i = 0; i <= p; ++i) EXPECT_EQ(ders[n * (p + 1) + i], 0.0);
      }
    }
  }
}

TEST(Basis, BernsteinOnSingleInterval) {
  // On [0,1] with clamped knots the basis is Bernstein: B_i^3(u) = C(3,i) u^i (1-u)^(3-i).
  const KnotVector kv(3, {0, 0, 0, 0, 1, 1, 1, 1});
  double N[4], d[8];
  const double u = 0.3;
  basis_values(kv.data(), 3, 3, u, N);
  const double ref[4] = {0.343, 3 * 0.3 * 0.49, 3 * 0.09 * 0.7, 0.027};
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(N[i], ref[i], 1e-15);
  basis_derivatives(kv.data(), 3, 3, u, 1, d);
  // d/du (1-u)^3 = -3 (1-u)^2
  EXPECT_NEAR(d[4], -3 * 0.49, 1e-14);
  EXPECT_NEAR(d[7], 3 * 0.09, 1e-14);
}

TEST(Basis, PrecomputedAndFirstDerivativeVariantsMatchTheTriangularScheme) {
  std::mt19937 rng(13);
  for (int p = 0; p <= 5; ++p) {
    const KnotVector kv = test::random_knots(p, 6, rng, 0.0, 3.0);
    std::vector<double> a(p + 1), b(p + 1), d(p + 1), ders(2 * (p + 1));
    for (int q = 0; q <= 300; ++q) {
      const double u = 3.0 * q / 300;
      const int s = kv.find_span(u);
      basis_values(kv.data(), p, s, u, a.data());
      basis_values(kv, s, u, b.data());
      basis_derivatives(kv.data(), p, s, u, 1, ders.data());
      std::vector<double> c(p + 1);
      basis_values_first_derivatives(kv, s, u, c.data(), d.data());
      for (int i = 0; i <= p; ++i) {
        EXPECT_NEAR(a[i], b[i], 1e-15);
        EXPECT_NEAR(c[i], a[i], 1e-15);
        EXPECT_NEAR(d[i], ders[p + 1 + i], 1e-12 * (1 + std::abs(d[i])));
      }
    }
  }
}

// The power form the evaluation kernels use (KnotVector::span_power_form), evaluated here by plain Horner's
// rule, against the triangular scheme: on random knots, on knots graded by a factor 10^4 from span to span,
// with a double interior knot, and on uniform knots; at the ends of every span and inside it.
TEST(Basis, SpanPowerFormMatchesTheTriangularScheme) {
  std::mt19937 rng(29);
  for (int p = 1; p <= KnotVector::kMaxPowerFormDegree; ++p) {
    std::vector<double> graded(p + 1, 0.0);
    for (double h = 1e-4; h < 2.0; h *= 10.0) graded.push_back(graded.back() + h);
    for (double h = 1.0; h > 1e-5; h /= 10.0) graded.push_back(graded.back() + h);
    graded.insert(graded.end(), p, graded.back());
    std::vector<double> doubled = test::random_knots(p, 5, rng).knots();
    if (p >= 2) doubled.insert(doubled.begin() + p + 2, doubled[p + 2]);
    for (const KnotVector& kv : {test::random_knots(p, 6, rng, -1.0, 2.0), KnotVector(p, graded),
                                 KnotVector(p, doubled), KnotVector::open_uniform(p, 7, -0.5, 3.0)}) {
      ASSERT_EQ(kv.span_power_form(kv.first_span()), kv.power_forms());
      for (int s = kv.first_span(); s <= kv.last_span(); ++s) {
        if (kv[s] == kv[s + 1]) continue;
        const double* b = kv.span_power_form(s);
        ASSERT_EQ(b[0], kv[s]);
        for (int q = 0; q <= 16; ++q) {
          const double u = q == 16 ? std::nextafter(kv[s + 1], kv[s]) : kv[s] + (kv[s + 1] - kv[s]) * q / 16.0;
          const double x = (u - b[0]) * b[1];
          std::vector<double> ref(p + 1), dref(2 * (p + 1));
          basis_values(kv.data(), p, s, u, ref.data());
          basis_derivatives(kv.data(), p, s, u, 1, dref.data());
          double dmax = 0.0;
          for (int a = 0; a <= p; ++a) dmax = std::max(dmax, std::abs(dref[p + 1 + a]));
          for (int a = 0; a <= p; ++a) {
            double n = 0.0, d = 0.0;
            for (int m = p; m >= 0; --m) n = n * x + b[2 + m * (p + 1) + a];
            for (int m = p - 1; m >= 0; --m) d = d * x + b[2 + (p + 1) * (p + 1) + m * (p + 1) + a];
            EXPECT_NEAR(n, ref[a], 1e-14) << "degree " << p << " span " << s << " u " << u;
            EXPECT_NEAR(d, dref[p + 1 + a], 1e-13 * dmax) << "degree " << p << " span " << s << " u " << u;
          }
        }
      }
    }
  }
  EXPECT_EQ(KnotVector::open_uniform(5, 3).power_forms(), nullptr);  // no kernel of degree 5
}
