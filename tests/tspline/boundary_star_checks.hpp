#pragma once
// Checks shared by the tests of star points on the boundary: end-condition block points moved off their vertices
// (the general clamped end), the boundary loops of a tessellation (a crack would add loops), and the spread of
// the star faces' normals at a star point.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>

#include "face_continuity.hpp"
#include "trivar/tspline/t_mesh_surface.hpp"
#include "trivar/tspline/t_spline_tessellation.hpp"

namespace trivar::test {

// Every end-condition block point moved by a random offset in [-offset, offset] per coordinate.
inline void offset_block_points(TMesh& m, unsigned seed, double offset = 0.2) {
  std::mt19937 g(seed);
  std::uniform_real_distribution<double> d(-offset, offset);
  for (const TMeshVertex& v : m.vertices)
    for (int b : v.block)
      if (b >= 0)
        for (double& c : m.points[static_cast<std::size_t>(b)].xyz) c += d(g);
}

// Edges used once form closed loops (the boundaries; a crack inside would add loops): their number.
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

// The star faces around star point `star` have one tangent plane there: the largest sine of the angle between
// their normals and the first one's.
inline double tangent_plane_spread(const TMeshSurface& s, int star) {
  std::array<double, 3> n0{};
  double worst = 0;
  for (int f = 0; f < s.num_faces(); ++f) {
    if (s.method(f) != FaceMethod::star) continue;
    const auto c4 = s.corners(f);
    const int corner = static_cast<int>(std::find(c4.begin(), c4.end(), star) - c4.begin());
    if (corner == 4) continue;
    const auto o = corner_frame(corner).origin;
    double x[9];
    s.eval(f, o[0], o[1], x);
    const auto n = unit_normal(x);
    if (n0 == std::array<double, 3>{}) n0 = n;
    worst = std::max(worst, std::hypot(n[1] * n0[2] - n[2] * n0[1], n[2] * n0[0] - n[0] * n0[2], n[0] * n0[1] - n[1] * n0[0]));
  }
  return worst;
}

}  // namespace trivar::test
