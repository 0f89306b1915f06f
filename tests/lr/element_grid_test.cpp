#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "trivar/lr/lr_mesh.hpp"

using namespace trivar;

namespace {

template <int D>
bool closed_boxes_meet(const Box<D>& a, const Box<D>& b) {
  for (int k = 0; k < D; ++k)
    if (a.hi[k] < b.lo[k] || b.hi[k] < a.lo[k]) return false;
  return true;
}

// A locally refined box partition of [0, 2]^D: every box with its lower corner in the ball of radius 0.7 about
// the origin is halved in every direction,
// `levels` times, so the cells near the corner hold many small boxes (the dense case query_dense splits), and
// box faces lie on cell and sub-cell bounds (2^-levels multiples). Boxes are added as they appear and then
// shrink in place (the grid keeps them listed where they were), as in a refinement.
template <int D>
void check_grid_against_brute_force(int levels, unsigned seed) {
  Box<D> domain;
  for (int k = 0; k < D; ++k) domain.lo[k] = 0.0, domain.hi[k] = 2.0;
  std::vector<Box<D>> boxes{domain};
  ElementGrid<D> plain(domain, 8), dense(domain, 8);
  plain.add(0, domain);
  dense.add(0, domain);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 2.0);
  std::uniform_int_distribution<int> grid_step(0, 16);
  const auto random_query = [&] {
    Box<D> q;
    for (int k = 0; k < D; ++k) {
      // Half of the bounds on a 1/8 grid (cell and sub-cell bounds), the rest anywhere; some queries flat.
      double a = grid_step(rng) % 2 ? unit(rng) : grid_step(rng) / 8.0, b = unit(rng) * 0.3;
      if (grid_step(rng) % 3 == 0) b = 0.0;
      q.lo[k] = std::clamp(a, 0.0, 2.0);
      q.hi[k] = std::clamp(a + b, 0.0, 2.0);
    }
    return q;
  };
  int fewer = 0;
  const auto check_queries = [&] {
    for (int t = 0; t < 25; ++t) {
      const Box<D> q = random_query();
      std::vector<int> expected, from_plain, from_dense;
      for (std::size_t i = 0; i < boxes.size(); ++i)
        if (closed_boxes_meet(boxes[i], q)) expected.push_back(static_cast<int>(i));
      plain.query(q, [&](int id) { from_plain.push_back(id); });
      dense.query_dense(q, [&](int id) -> const Box<D>& { return boxes[static_cast<std::size_t>(id)]; },
                        [&](int id) { from_dense.push_back(id); });
      for (auto* got : {&from_plain, &from_dense}) {
        std::sort(got->begin(), got->end());
        EXPECT_TRUE(std::adjacent_find(got->begin(), got->end()) == got->end()) << "an id reported twice";
        EXPECT_TRUE(std::includes(got->begin(), got->end(), expected.begin(), expected.end()))
            << "a box meeting the query is missing";
      }
      // The dense grid's candidates are never more than the plain grid's, and fewer where it split cells.
      EXPECT_LE(from_dense.size(), from_plain.size());
      fewer += from_dense.size() < from_plain.size() ? 1 : 0;
    }
  };
  for (int level = 0; level < levels; ++level) {
    const double r = 0.7;
    const std::size_t n = boxes.size();
    for (std::size_t i = 0; i < n; ++i) {
      double dist = 0.0;
      for (int k = 0; k < D; ++k) dist += boxes[i].lo[k] * boxes[i].lo[k];
      if (dist >= r * r) continue;
      // Box i into 2^D pieces: every piece so far halved in each direction in turn.
      std::vector<std::size_t> pieces{i};
      for (int k = 0; k < D; ++k)
        for (std::size_t j = 0, count = pieces.size(); j < count; ++j) {
          Box<D>& lower = boxes[pieces[j]];
          Box<D> upper = lower;
          upper.lo[k] = lower.hi[k] = 0.5 * (lower.lo[k] + lower.hi[k]);
          pieces.push_back(boxes.size());
          boxes.push_back(upper);
          plain.add(static_cast<int>(boxes.size()) - 1, upper);
          dense.add(static_cast<int>(boxes.size()) - 1, upper);
        }
      if (i % 61 == 0) check_queries();
    }
    check_queries();
  }
  EXPECT_GT(boxes.size(), std::size_t{1000});
  EXPECT_GT(fewer, 0) << "no query reached a split cell";
}

}  // namespace

TEST(ElementGrid, QueriesReportEveryMeetingBoxOnceOnALocallyRefinedPartition) {
  check_grid_against_brute_force<2>(7, 11);
  check_grid_against_brute_force<3>(5, 12);
}
