#include "trivar/lr/selection.hpp"

#include <gtest/gtest.h>

#include "trivar/core/error.hpp"

using namespace trivar;

namespace {

LRSpline<3> unit_cube(int p, int n) {
  const auto kv = KnotVector::open_uniform(p, n);
  const int m = kv.size();
  return LRSpline<3>(TensorSpline<3>({kv, kv, kv}, 1, false, std::vector<double>(static_cast<std::size_t>(m * m * m), 1.0)));
}

}  // namespace

TEST(LRSelection, SegmentBoxTestUsesOpenBoxes) {
  const Box<2> b{{0.0, 0.0}, {1.0, 1.0}};
  EXPECT_TRUE(segment_meets_open<2>({-1, 0.5}, {2, 0.5}, b));
  EXPECT_FALSE(segment_meets_open<2>({-1, 1.0}, {2, 1.0}, b));   // along the top edge
  EXPECT_FALSE(segment_meets_open<2>({1, 1}, {2, 2}, b));        // touches the corner only
  EXPECT_FALSE(segment_meets_open<2>({1.5, 1.5}, {1.2, 0.5}, b)); // stops before the box
  EXPECT_TRUE(segment_meets_open<2>({1.5, 1.5}, {0.9, 0.1}, b));
  EXPECT_TRUE(segment_meets_open<2>({0.2, 0.3}, {0.2, 0.3}, b));  // a point inside
  EXPECT_FALSE(segment_meets_open<2>({-0.5, 0.5}, {0.0, 1.0}, b)); // ends at the boundary
  EXPECT_TRUE(segment_meets_open<2>({-0.5, 0.5}, {0.0, 0.5 + 1e-9}, Box<2>{{-1, 0}, {1, 1}}));
}

TEST(LRSelection, DiagonalOfUniformMesh) {
  const auto lr = unit_cube(3, 4);
  const auto el = elements_on_segment(lr, {0, 0, 0}, {1, 1, 1});
  ASSERT_EQ(el.size(), 4u);  // the diagonal crosses exactly the diagonal elements, touching the others at corners
  for (int e : el) {
    const auto& b = lr.element(e);
    EXPECT_EQ(b.lo[0], b.lo[1]);
    EXPECT_EQ(b.lo[1], b.lo[2]);
  }
  // Cubic supports [t_i, t_{i+4}] per direction meet the diagonal's open interior exactly when the three
  // intervals overlap with positive length: count by hand over the 7^3 index triples.
  std::vector<std::pair<double, double>> iv;
  const auto kv = KnotVector::open_uniform(3, 4);
  for (int i = 0; i < kv.size(); ++i) iv.push_back({kv.knots()[static_cast<std::size_t>(i)], kv.knots()[static_cast<std::size_t>(i) + 4]});
  std::size_t expect = 0;
  for (auto a : iv)
    for (auto b : iv)
      for (auto c : iv)
        if (std::max({a.first, b.first, c.first}) < std::min({a.second, b.second, c.second})) ++expect;
  EXPECT_EQ(functions_on_segment(lr, {0, 0, 0}, {1, 1, 1}).size(), expect);
}

TEST(LRSelection, BoxSelectionAndIds) {
  const auto lr = unit_cube(2, 4);
  EXPECT_EQ(elements_in_box(lr, Box<3>{{0.1, 0.1, 0.1}, {0.2, 0.2, 0.2}}).size(), 1u);
  EXPECT_EQ(elements_in_box(lr, Box<3>{{0.25, 0.25, 0.25}, {0.25, 0.25, 0.25}}).size(), 0u);  // a corner point
  EXPECT_EQ(elements_in_box(lr, Box<3>{{0.2, 0.2, 0.2}, {0.3, 0.3, 0.3}}).size(), 8u);
  // Quadratic supports [t_i, t_{i+3}] containing 0.1 in their open interior: i = 0, 1, 2 per direction.
  EXPECT_EQ(functions_in_box(lr, Box<3>{{0.1, 0.1, 0.1}, {0.1, 0.1, 0.1}}).size(), 27u);
  const std::vector<int> ids{5, 1, 5, 3};
  EXPECT_EQ(checked_ids(ids, 6, "element"), (std::vector<int>{1, 3, 5}));
  const std::vector<int> bad{0, 6};
  EXPECT_THROW(checked_ids(bad, 6, "element"), Error);
}
