#include "trivar/spline/knot_refinement.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <gmpxx.h>

#include "support/spline_fixtures.hpp"
#include "trivar/core/error.hpp"

using namespace trivar;

namespace {

// B[y](u) by the Cox-de Boor recursion of the test fixtures (u strictly inside the knots' range).
double bspline(const std::vector<double>& y, double u) {
  return test::cox_de_boor(y, 0, static_cast<int>(y.size()) - 2, u, y.back());
}

// sum_j c_j B[fine_j .. fine_{j+p+1}](u).
double expansion(const std::vector<double>& fine, int p, const std::vector<double>& c, double u) {
  double v = 0.0;
  for (std::size_t j = 0; j < c.size(); ++j)
    v += c[j] * bspline(std::vector<double>(fine.begin() + static_cast<std::ptrdiff_t>(j),
                                            fine.begin() + static_cast<std::ptrdiff_t>(j) + p + 2),
                        u);
  return v;
}

}  // namespace

// An exact split: local knots with further knots inserted (new values, repeated values, raised multiplicities)
// give the same function on the whole line, checked against Cox-de Boor on both sides.
TEST(KnotRefinement, ExpressInSplitsExactly) {
  std::mt19937 rng(7);
  for (int p = 0; p <= 5; ++p)
    for (int trial = 0; trial < 20; ++trial) {
      std::vector<double> y;
      for (int i = 0; i < p + 2; ++i) y.push_back(std::uniform_int_distribution<int>(0, 6)(rng) * 0.5);
      std::sort(y.begin(), y.end());
      if (y.front() == y.back()) continue;
      std::vector<double> fine = y;
      const int extra = std::uniform_int_distribution<int>(1, 4)(rng);
      for (int i = 0; i < extra; ++i) {
        // Inside the support: a fresh value, or a copy of an interior knot while its multiplicity stays <= p + 1.
        const double z = std::uniform_real_distribution<double>(y.front(), y.back())(rng);
        const double v = (i % 2 == 0 || p + 2 <= 2) ? z : y[static_cast<std::size_t>(1 + i % p)];
        if (!(y.front() < v && v < y.back()) || std::count(fine.begin(), fine.end(), v) > p) continue;
        fine.insert(std::upper_bound(fine.begin(), fine.end(), v), v);
      }
      std::vector<double> c(fine.size() - static_cast<std::size_t>(p) - 1);
      express_in<double>(y, fine, c.data());
      for (double x : c) EXPECT_GE(x, 0.0);
      for (int q = 0; q < 25; ++q) {
        const double u = std::uniform_real_distribution<double>(y.front() - 0.5, y.back() + 0.5)(rng);
        EXPECT_NEAR(expansion(fine, p, c, u), u < y.back() ? bspline(y, u) : 0.0, 1e-13) << "p " << p;
      }
    }
}

// A restriction: the finer sequence covers only a part [fine_p, fine_n] of the support, with (p + 1)-fold
// ends; the identity holds there. With no knot inside, the coefficients are the Bernstein form on [a, b].
TEST(KnotRefinement, ExpressInRestrictsToAPartOfTheSupport) {
  std::mt19937 rng(8);
  const std::vector<std::vector<double>> knots = {{0, 1, 3, 4}, {0, 0, 0, 2}, {0, 2, 2, 2}, {0, 1, 1, 2, 5}, {1, 2},
                                                  {0, 0.5, 1.5, 2, 3.5, 4}};
  for (const auto& y : knots) {
    const int p = static_cast<int>(y.size()) - 2;
    std::vector<double> bp(y);
    bp.erase(std::unique(bp.begin(), bp.end()), bp.end());
    for (std::size_t i = 0; i + 1 < bp.size(); ++i) {
      const double a = bp[i], b = bp[i + 1];
      std::vector<double> row(static_cast<std::size_t>(p + 1));
      bernstein_coefficients<double>(y, a, b, row.data());
      for (int q = 0; q < 7; ++q) {
        const double u = std::uniform_real_distribution<double>(a, b)(rng), x = (u - a) / (b - a);
        double bern = 0.0;
        for (int j = 0; j <= p; ++j)
          bern += row[static_cast<std::size_t>(j)] * std::tgamma(p + 1) / (std::tgamma(j + 1) * std::tgamma(p - j + 1)) *
                  std::pow(x, j) * std::pow(1 - x, p - j);
        EXPECT_NEAR(bern, bspline(y, u), 1e-14);
      }
    }
    // Several knot intervals at once: [bp[0], bp.back()] with the breakpoints inside, (p + 1)-fold ends.
    std::vector<double> fine(static_cast<std::size_t>(p + 1), bp.front());
    for (double t : y)
      if (bp.front() < t && t < bp.back()) fine.push_back(t);
    fine.insert(fine.end(), static_cast<std::size_t>(p + 1), bp.back());
    std::vector<double> c(fine.size() - static_cast<std::size_t>(p) - 1);
    express_in<double>(y, fine, c.data());
    for (int q = 0; q < 25; ++q) {
      const double u = std::uniform_real_distribution<double>(bp.front(), bp.back())(rng);
      EXPECT_NEAR(expansion(fine, p, c, u), bspline(y, u), 1e-13);
    }
  }
}

// Known values: the cubic cardinal B-spline on [0,4] has the Bezier points 1/6, 1/3, 2/3, 2/3 on [1,2], and
// halving every interval gives the subdivision mask (1, 4, 6, 4, 1) / 8.
TEST(KnotRefinement, CardinalCubicKnownCoefficients) {
  const std::vector<double> y{0, 1, 2, 3, 4};
  double row[4];
  bernstein_coefficients<double>(y, 1.0, 2.0, row);
  EXPECT_NEAR(row[0], 1.0 / 6, 1e-15);
  EXPECT_NEAR(row[1], 1.0 / 3, 1e-15);
  EXPECT_NEAR(row[2], 2.0 / 3, 1e-15);
  EXPECT_NEAR(row[3], 2.0 / 3, 1e-15);
  const std::vector<double> fine{0, 0.5, 1, 1.5, 2, 2.5, 3, 3.5, 4};
  double c[5];
  express_in<double>(y, fine, c);
  const double mask[5] = {1, 4, 6, 4, 1};
  for (int j = 0; j < 5; ++j) EXPECT_NEAR(c[j], mask[j] / 8, 1e-15);
}

// The knot-vector form: a B-spline of a knot vector written in a refinement of it (the first index and the
// coefficients), and refusal of a target that lacks one of its knots.
TEST(KnotRefinement, ExpressInAKnotVector) {
  const KnotVector to(2, {0, 0, 0, 0.5, 1, 1, 1.5, 2, 2, 2});
  int first = -1;
  std::vector<double> c;
  express_in(std::vector<double>{0.5, 1, 2, 2}, 2, to, first, c);
  EXPECT_EQ(first, 3);  // B[0.5 1 1 1.5] is the first B-spline of `to` starting at 0.5
  ASSERT_EQ(c.size(), 3u);
  for (int q = 0; q <= 20; ++q) {
    const double u = 0.5 + 0.07 * q;
    EXPECT_NEAR(expansion(to.knots(), 2, [&] {
                  std::vector<double> all(static_cast<std::size_t>(to.size()), 0.0);
                  std::copy(c.begin(), c.end(), all.begin() + first);
                  return all;
                }(), u),
                bspline({0.5, 1, 2, 2}, u), 1e-14);
  }
  EXPECT_THROW(express_in(std::vector<double>{0, 0.25, 1, 2}, 2, to, first, c), Error);
}

// In rational arithmetic the coefficients are exact: the known values above hold as equalities of rationals,
// and the Bernstein coefficients of a B-spline with non-dyadic spacing come out as the exact fractions.
TEST(KnotRefinement, ExactCoefficientsInRationalArithmetic) {
  const std::vector<double> y{0, 1, 2, 3, 4};
  mpq_class row[4];
  bernstein_coefficients<mpq_class>(y, 1.0, 2.0, row);
  EXPECT_EQ(row[0], mpq_class(1, 6));
  EXPECT_EQ(row[1], mpq_class(1, 3));
  EXPECT_EQ(row[2], mpq_class(2, 3));
  EXPECT_EQ(row[3], mpq_class(2, 3));
  mpq_class c[5];
  express_in<mpq_class>(y, std::vector<double>{0, 0.5, 1, 1.5, 2, 2.5, 3, 3.5, 4}, c);
  const int mask[5] = {1, 4, 6, 4, 1};
  for (int j = 0; j < 5; ++j) EXPECT_EQ(c[j], mpq_class(mask[j]) / 8);
  // Quadratic B[0 1 3 4] on [1, 3]: value at 1 is 1/3, the middle Bernstein coefficient is the blossom
  // b(1, 3) = 1, and the value at 3 is 1/3 (by symmetry).
  mpq_class q[3];
  bernstein_coefficients<mpq_class>(std::vector<double>{0, 1, 3, 4}, 1.0, 3.0, q);
  EXPECT_EQ(q[0], mpq_class(1, 3));
  EXPECT_EQ(q[1], mpq_class(1));
  EXPECT_EQ(q[2], mpq_class(1, 3));
}
