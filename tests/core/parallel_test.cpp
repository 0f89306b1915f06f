// parallel_for: every index once whatever the thread count, and an exception in the body reaches the caller
// instead of terminating the program inside the OpenMP region.
#include <gtest/gtest.h>

#include <atomic>
#include <new>
#include <vector>

#include "trivar/core/error.hpp"
#include "trivar/core/parallel.hpp"

using namespace trivar;

TEST(ParallelFor, VisitsEveryIndexOnce) {
  for (const int threads : {1, 2, 4}) {
    std::vector<std::atomic<int>> hits(1000);
    parallel_for(1000, threads, [&](std::ptrdiff_t i) { ++hits[static_cast<std::size_t>(i)]; });
    for (const auto& h : hits) ASSERT_EQ(h.load(), 1) << threads << " threads";
  }
}

TEST(ParallelFor, ExceptionsReachTheCaller) {
  for (const int threads : {1, 2, 4}) {
    EXPECT_THROW(parallel_for(1000, threads, [](std::ptrdiff_t i) { require(i != 637, "index 637"); }), Error);
    EXPECT_THROW(parallel_for(1000, threads, [](std::ptrdiff_t i) {
                   if (i % 100 == 99) throw std::bad_alloc();
                 }),
                 std::bad_alloc);
    try {
      parallel_for(1000, threads, [](std::ptrdiff_t i) { require(i != 5, "index 5 failed"); });
      ADD_FAILURE() << "no exception";
    } catch (const Error& e) {
      EXPECT_STREQ(e.what(), "index 5 failed");
    }
  }
}
