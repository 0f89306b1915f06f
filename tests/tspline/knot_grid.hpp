#pragma once
// Quad grids on given knot positions with a wavy surface as points, and their meshes with a crease boundary.
#include <array>
#include <cmath>
#include <vector>

#include "star_mesh_tsm.hpp"
#include "trivar/io/tsm_format.hpp"
#include "trivar/tspline/t_mesh.hpp"

namespace trivar::test {

inline double wave(double x, double y) { return 0.4 * std::sin(0.9 * x + 0.3) * std::cos(0.6 * y - 0.2) + 0.03 * x * y; }

// The mesh of a TSM text read with its end-condition blocks dropped and the crease flag set (what Fusion writes:
// no grip blocks).
inline TMesh crease_mesh(const QuadMesh& q) {
  TMesh m = io::parse_tsm(tsm_text(q), "crease.tsm").mesh;
  m.end_conditions = EndConditions::subd_creases;
  for (TMeshVertex& v : m.vertices) {
    v.block.clear();
    v.block_dims = {};
  }
  return m;
}

// A grid of faces on the knot positions s (columns) x t (rows): vertex i + j * s.size() at parameter (s[i], t[j]),
// its point a wavy surface over a slightly sheared (s, t) (so points and parameters differ).
struct Grid {
  std::vector<double> s, t;
  QuadMesh quads;
  int id(int i, int j) const { return i + j * static_cast<int>(s.size()); }
};

inline Grid grid(std::vector<double> s, std::vector<double> t) {
  Grid g{std::move(s), std::move(t), {}};
  const int ns = static_cast<int>(g.s.size()), nt = static_cast<int>(g.t.size());
  for (int j = 0; j < nt; ++j)
    for (int i = 0; i < ns; ++i) {
      const double x = g.s[i] + 0.1 * g.t[j], y = g.t[j] - 0.05 * g.s[i];
      g.quads.points.push_back({x, y, wave(x, y)});
    }
  for (int j = 0; j + 1 < nt; ++j)
    for (int i = 0; i + 1 < ns; ++i) {
      g.quads.quads.push_back({g.id(i, j), g.id(i + 1, j), g.id(i + 1, j + 1), g.id(i, j + 1)});
      g.quads.intervals[{g.id(i, j), g.id(i + 1, j)}] = g.quads.intervals[{g.id(i, j + 1), g.id(i + 1, j + 1)}] = g.s[i + 1] - g.s[i];
      g.quads.intervals[{g.id(i, j), g.id(i, j + 1)}] = g.quads.intervals[{g.id(i + 1, j), g.id(i + 1, j + 1)}] = g.t[j + 1] - g.t[j];
    }
  return g;
}

}  // namespace trivar::test
