#pragma once
// A T-mesh's half-edge links built face by face from vertex loops, for meshes made by refinement (global
// subdivision steps, completed T-junction lines): each face's links counter-clockwise, and each edge shared with
// the link added before it back along the same two vertices; then the outside links of the boundary, if any.
#include <span>
#include <unordered_map>
#include <unordered_set>

#include "trivar/tspline/t_mesh.hpp"

namespace trivar {

class LinkBuilder {
public:
  explicit LinkBuilder(TMesh& m) : m_(m) {}
  // Appends the face with vertices `loop` counter-clockwise from a corner (its first corner link), `straight[i]`
  // when the face's angle at loop[i] is 180 degrees (a T-junction of a neighbour on its side), and the knot
  // interval from loop[i] to the next (taken when that edge is new). Returns the face's id.
  int add_face(std::span<const int> loop, std::span<const char> straight, std::span<const double> interval);
  // Edge a -> b is not joined with an edge b -> a (the two sides of a sharp edge between two darts).
  void keep_apart(int a, int b) { apart_.insert(static_cast<long long>(a) * (1LL << 32) + b); }
  // The outside link (face -1) of every edge with one face, linked round the boundary, its flag the outside angle
  // at its vertex (angle / 90 - 1). Throws trivar::Error at a vertex on two boundary arcs.
  void close_boundary();

private:
  TMesh& m_;
  std::unordered_map<long long, int> by_ends_;  // (from, to) -> link
  std::unordered_set<long long> apart_;
};

}  // namespace trivar
