#include "trivar/core/memory_budget.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "trivar/core/error.hpp"

using namespace trivar;

TEST(MemoryBudget, FormatsBytesInBinaryUnits) {
  EXPECT_EQ(format_bytes(12), "12 bytes");
  EXPECT_EQ(format_bytes(4096), "4.0 KiB");
  EXPECT_EQ(format_bytes(1.5 * 1024 * 1024 * 1024), "1.5 GiB");
  EXPECT_EQ(format_bytes(312.0 * 1024 * 1024), "312 MiB");
}

TEST(MemoryBudget, RefusesARequestLargerThanWhatIsAvailableAndNamesIt) {
  EXPECT_NO_THROW(require_memory(1000, "a small grid", 2000));
  try {
    require_memory(8.0 * 2000 * 2000 * 2000 * 3, "a 2000 x 2000 x 2000 control grid", 24.0 * 1024 * 1024 * 1024);
    FAIL() << "expected a refusal";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "a 2000 x 2000 x 2000 control grid would need 179 GiB of memory, more than the 24 GiB available");
  }
  EXPECT_THROW(require_memory(std::numeric_limits<double>::infinity(), "an unbounded request", 1e12), Error);
  EXPECT_THROW(require_memory(std::numeric_limits<double>::quiet_NaN(), "a NaN request", 1e12), Error);
}

TEST(MemoryBudget, AvailableMemoryIsPositiveOnThisSystem) { EXPECT_GT(available_memory_bytes(), 0.0); }
