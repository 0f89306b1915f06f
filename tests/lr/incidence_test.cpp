#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <span>
#include <vector>

#include "trivar/lr/incidence.hpp"

using namespace trivar;

namespace {

// num_lists lists of distinct ids below num_ids, in random order, some empty.
std::vector<std::vector<int>> random_lists(int num_lists, int num_ids, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<int> all(static_cast<std::size_t>(num_ids));
  for (int j = 0; j < num_ids; ++j) all[static_cast<std::size_t>(j)] = j;
  std::vector<std::vector<int>> lists;
  for (int i = 0; i < num_lists; ++i) {
    std::shuffle(all.begin(), all.end(), rng);
    const auto n = static_cast<std::size_t>(std::uniform_int_distribution<int>(0, num_ids / 3)(rng));
    lists.emplace_back(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(n));
  }
  return lists;
}

// The transpose by its definition: list t holds, ascending, every kept i whose list holds some j renamed to t.
std::vector<std::vector<int>> by_membership(const std::vector<std::vector<int>>& lists, int num_targets,
                                            const std::vector<char>& keep, const std::vector<int>& rename) {
  std::vector<std::vector<int>> t(static_cast<std::size_t>(num_targets));
  for (int target = 0; target < num_targets; ++target)
    for (std::size_t i = 0; i < lists.size(); ++i)
      if (keep[i])
        for (int j : lists[i])
          if (rename[static_cast<std::size_t>(j)] == target)
            t[static_cast<std::size_t>(target)].push_back(static_cast<int>(i));
  return t;
}

void expect_lists(const Incidence& got, const std::vector<std::vector<int>>& want) {
  ASSERT_EQ(got.size(), static_cast<int>(want.size()));
  EXPECT_EQ(got.offsets.front(), 0);
  EXPECT_EQ(got.offsets.back(), static_cast<int>(got.ids.size()));
  for (int t = 0; t < got.size(); ++t) {
    const auto list = got[t];
    EXPECT_EQ(std::vector<int>(list.begin(), list.end()), want[static_cast<std::size_t>(t)]) << "list " << t;
  }
}

}  // namespace

TEST(Incidence, TransposeIntoLeavesOutRenamesAndReusesStorage) {
  const int num_lists = 60, num_ids = 40;
  const auto lists = random_lists(num_lists, num_ids, 7);
  std::mt19937 rng(11);
  std::vector<char> keep(static_cast<std::size_t>(num_lists));
  for (auto& k : keep) k = static_cast<char>(rng() % 4 != 0);
  std::vector<int> rename(static_cast<std::size_t>(num_ids));
  for (int j = 0; j < num_ids; ++j) rename[static_cast<std::size_t>(j)] = j;
  std::shuffle(rename.begin(), rename.end(), rng);
  const auto want = by_membership(lists, num_ids, keep, rename);
  const auto list = [&](int i) {
    return keep[static_cast<std::size_t>(i)] ? std::span<const int>(lists[static_cast<std::size_t>(i)])
                                             : std::span<const int>{};
  };
  const auto renamed = [&](int j) { return rename[static_cast<std::size_t>(j)]; };

  // Into storage that holds stale, larger lists: the result overwrites them in place.
  Incidence out;
  out.offsets.assign(100, 5);
  out.ids.assign(5000, -1);
  const int* storage = out.ids.data();
  transpose_into(out, num_ids, num_lists, list, renamed);
  expect_lists(out, want);
  EXPECT_EQ(out.ids.data(), storage);

  // The same with the lengths of the result given instead of counted.
  std::vector<int> sizes;
  for (const auto& w : want) sizes.push_back(static_cast<int>(w.size()));
  Incidence given;
  transpose_into(given, num_ids, num_lists, list, renamed, sizes);
  expect_lists(given, want);
}

TEST(Incidence, TransposedTwiceGivesTheSortedLists) {
  auto lists = random_lists(50, 30, 3);
  Incidence in;
  for (auto& l : lists) {
    in.ids.insert(in.ids.end(), l.begin(), l.end());
    in.offsets.push_back(static_cast<int>(in.ids.size()));
    std::sort(l.begin(), l.end());
  }
  std::vector<int> same(30);
  for (int j = 0; j < 30; ++j) same[static_cast<std::size_t>(j)] = j;
  const Incidence t = in.transposed(30);
  expect_lists(t, by_membership(lists, 30, std::vector<char>(50, 1), same));
  expect_lists(t.transposed(50), lists);
  // No lists at all, and targets no list names.
  expect_lists(Incidence{}.transposed(3), {{}, {}, {}});
}
