#pragma once
// The boundary loops of a triangulation: edges used once (without their reverse) chained into closed loops. A
// watertight tessellation of a surface with one boundary has one; a crack inside adds loops. And the Euler
// characteristic of a closed one.
#include <array>
#include <map>

#include <gtest/gtest.h>

#include "trivar/tspline/t_spline_tessellation.hpp"

namespace trivar::test {

// Their number; -1 when a chain does not close.
inline int boundary_loops(const TSplineTriangulation& t) {
  std::map<std::array<int, 2>, int> use;
  for (const auto& tri : t.triangles)
    for (int k = 0; k < 3; ++k) ++use[{tri[static_cast<std::size_t>(k)], tri[static_cast<std::size_t>((k + 1) % 3)]}];
  std::map<int, int> next;
  for (const auto& [e, n] : use) {
    EXPECT_EQ(n, 1) << "edge used twice in the same direction";
    if (!use.count({e[1], e[0]})) {
      EXPECT_EQ(next.count(e[0]), 0u) << "boundary vertex with two outgoing edges";
      next[e[0]] = e[1];
    }
  }
  std::map<int, char> seen;
  int loops = 0;
  for (const auto& [start, to] : next) {
    if (seen.count(start)) continue;
    ++loops;
    int v = start;
    do {
      seen[v] = 1;
      const auto it = next.find(v);
      if (it == next.end()) return -1;  // an open boundary chain
      v = it->second;
    } while (v != start && seen.size() <= next.size());
  }
  return loops;
}

// V - E + F of a closed, orientable two-manifold triangulation (every directed edge once, its reverse present).
inline long closed_euler_characteristic(const TSplineTriangulation& t) {
  std::map<std::array<int, 2>, int> directed;
  for (const auto& tri : t.triangles)
    for (int k = 0; k < 3; ++k) ++directed[{tri[static_cast<std::size_t>(k)], tri[static_cast<std::size_t>((k + 1) % 3)]}];
  for (const auto& [e, n] : directed) {
    EXPECT_EQ(n, 1) << "edge " << e[0] << "-" << e[1] << " used twice in one direction";
    EXPECT_EQ(directed.count({e[1], e[0]}), 1u) << "boundary edge " << e[0] << "-" << e[1];
  }
  return static_cast<long>(t.points.size()) - static_cast<long>(directed.size() / 2) + static_cast<long>(t.triangles.size());
}

}  // namespace trivar::test
