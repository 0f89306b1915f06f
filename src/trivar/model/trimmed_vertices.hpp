#pragma once
// The vertices of one trimmed boundary (seed 001: the V-points of a trimmed cell). A TrimmedBoundary stores
// faces, loops and edges but no vertices: they follow from the loops, where one trim curve ends and the next
// begins (a degenerate curve, a pole, is passed through), so two edge ends are one vertex exactly when a loop
// joins them. Positions are the mean of the edge ends joined (the 3D edge curves, or the trim curve on its
// surface for an edge stored without a curve). Edges no loop uses are not part of the boundary.
#include <array>
#include <vector>

#include "trivar/model/trimmed_boundary.hpp"

namespace trivar {

struct TrimmedVertices {
  std::vector<std::array<double, 3>> positions;  // per vertex
  std::vector<std::array<int, 2>> edge_vertices;  // per edge: start and end vertex ({-1, -1} when unused)
  // Per edge: the faces whose loops use it, once per use, ascending (a seam appears twice for its face).
  std::vector<std::vector<int>> edge_faces;
  // Per edge: its two ends in space (start, end), as the curve gives them.
  std::vector<std::array<std::array<double, 3>, 2>> edge_ends;
  int used_edges = 0;
  // V - E + sum over faces of (2 - loops): 2 for a boundary that is one sphere-like surface, 0 for a torus-like
  // one (each face a planar region of its parameter domain, its loops its boundary).
  int euler_characteristic = 0;
};

TrimmedVertices trimmed_vertices(const TrimmedBoundary& b);

}  // namespace trivar
