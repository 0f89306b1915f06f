// Reference cycles are legal P21; the cycle finder reports them for mappers that need acyclic data.
#include <gtest/gtest.h>

#include "step/step_test_support.hpp"
#include "trivar/io/step/id_set.hpp"
#include "trivar/io/step/parser.hpp"
#include "trivar/io/step/reference_cycles.hpp"

using namespace trivar;
using namespace trivar::io::step;

TEST(StepReferenceCycles, CyclesAreReadAndFound) {
  const ExchangeFile f = read_exchange_file(test::step_data("cycle.stp"));  // legal: no exception
  EXPECT_EQ(find_reference_cycle(f, 1), (std::vector<std::uint64_t>{1, 2, 3, 1}));
  EXPECT_EQ(find_reference_cycle(f, 3), (std::vector<std::uint64_t>{3, 1, 2, 3}));
  EXPECT_TRUE(find_reference_cycle(f, 5).empty());  // a diamond (#4 twice) is not a cycle
  EXPECT_TRUE(find_reference_cycle(f, 4).empty());
  EXPECT_EQ(find_reference_cycle(f).size(), 4u);
}

TEST(StepReferenceCycles, SelfReferenceAndLongChains) {
  std::string data = "#1=SELF(#1);\n";
  for (int k = 2; k < 100000; ++k) {  // appended piecewise: GCC 12 warns falsely on "#" + std::string
    data += '#';
    data += std::to_string(k);
    data += "=C(#";
    data += std::to_string(k + 1);
    data += ");\n";
  }
  data += "#100000=END();";
  const ExchangeFile f = parse_exchange_file(test::step_file(data));
  EXPECT_EQ(find_reference_cycle(f, 1), (std::vector<std::uint64_t>{1, 1}));
  EXPECT_TRUE(find_reference_cycle(f, 2).empty());  // 10^5 deep: iterative search does not overflow
}

TEST(StepIdSet, IntervalsMergeAndDetectDuplicates) {
  IdSet s;
  for (std::uint64_t id : {1, 2, 3, 10, 11, 5, 4, 7, 9, 8, 6}) EXPECT_TRUE(s.insert(id)) << id;
  EXPECT_EQ(s.intervals(), 1u);  // 1..11
  for (std::uint64_t id = 1; id <= 11; ++id) EXPECT_FALSE(s.insert(id));
  EXPECT_FALSE(s.contains(0));
  EXPECT_FALSE(s.contains(12));
  EXPECT_TRUE(s.insert(1000));
  EXPECT_TRUE(s.insert(13));
  EXPECT_EQ(s.intervals(), 3u);
  EXPECT_TRUE(s.contains(1000));
  EXPECT_FALSE(s.contains(999));
  EXPECT_TRUE(s.insert(12));
  EXPECT_EQ(s.intervals(), 2u);
}
