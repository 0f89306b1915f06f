#include "trivar/core/clamped_count.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace trivar {
namespace {

// Ceilings inside [lo, hi]; estimates beyond either end, infinite or NaN give the end (no conversion of an
// out-of-range double to int, which is undefined behaviour: the tessellations met 1.1e22 from a file).
TEST(ClampedCount, CeilingWithinTheBounds) {
  EXPECT_EQ(clamped_count(2.2, 1, 64), 3);
  EXPECT_EQ(clamped_count(3.0, 1, 64), 3);
  EXPECT_EQ(clamped_count(0.1, 1, 64), 1);
  EXPECT_EQ(clamped_count(-5e30, 1, 64), 1);
  EXPECT_EQ(clamped_count(64.0, 1, 64), 64);
  EXPECT_EQ(clamped_count(1.1e22, 1, 64), 64);
  EXPECT_EQ(clamped_count(std::numeric_limits<double>::infinity(), 1, 64), 64);
  EXPECT_EQ(clamped_count(std::numeric_limits<double>::quiet_NaN(), 1, 64), 64);
}

}  // namespace
}  // namespace trivar
