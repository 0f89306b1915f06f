#include "trivar/lr/dorfler.hpp"

#include <gtest/gtest.h>

#include "trivar/core/error.hpp"

using namespace trivar;

TEST(Dorfler, SmallestSetReachingTheFractionOfSquares) {
  // Squares 16, 9, 4, 1, 0 (total 30).
  const std::vector<double> eta{1, 4, 0, 3, 2};
  EXPECT_EQ(dorfler_mark(eta, 0.5), (std::vector<int>{1}));        // 16 >= 15
  EXPECT_EQ(dorfler_mark(eta, 0.6), (std::vector<int>{1, 3}));     // 25 >= 18
  EXPECT_EQ(dorfler_mark(eta, 0.9), (std::vector<int>{1, 3, 4}));  // 29 >= 27
  EXPECT_EQ(dorfler_mark(eta, 1.0), (std::vector<int>{0, 1, 3, 4}));
  // Ties go to the lower id.
  const std::vector<double> tie{2, 1, 2, 2};
  EXPECT_EQ(dorfler_mark(tie, 0.3), (std::vector<int>{0}));
  EXPECT_EQ(dorfler_mark(tie, 0.5), (std::vector<int>{0, 2}));
  EXPECT_TRUE(dorfler_mark(std::vector<double>{0, 0}, 1.0).empty());
}

TEST(Dorfler, InvalidInput) {
  const std::vector<double> eta{1, 2};
  EXPECT_THROW(dorfler_mark(eta, 0.0), Error);
  EXPECT_THROW(dorfler_mark(eta, 1.5), Error);
  EXPECT_THROW(dorfler_mark(std::vector<double>{1, -1}, 0.5), Error);
  const auto kv = KnotVector::open_uniform(2, 3);
  LRSpline<2> lr(TensorSpline<2>({kv, kv}, 1, false, std::vector<double>(25, 1.0)));
  EXPECT_THROW(refine_dorfler(lr, eta, 0.5, RefineOptions{}), Error);  // 2 indicators for 9 elements
}

TEST(Dorfler, RefinesTheMarkedElements) {
  const auto kv = KnotVector::open_uniform(2, 3);
  LRSpline<2> lr(TensorSpline<2>({kv, kv}, 1, false, std::vector<double>(25, 1.0)));
  std::vector<double> eta(9, 0.0);
  eta[4] = 1.0;  // the centre element only
  // Its supports span the whole domain, so FULLSPAN inserts the full lines x = 1/2 and y = 1/2: the tensor
  // mesh with 4 x 4 elements and 6 x 6 B-splines.
  EXPECT_EQ(refine_dorfler(lr, eta, 1.0, RefineOptions{}), 2);
  EXPECT_EQ(lr.num_elements(), 16);
  EXPECT_EQ(lr.num_basis(), 36);
}
