#pragma once
// The topological layer of a T-spline (Xiao et al. 2016): the T-connect. A T-node is one blending function:
// it sits on a T-vertex, a T-link or a T-face of the T-image (odd degree in both directions: a vertex; odd in
// one and even in the other: a link across the even direction; even in both: a face), names its rational point
// in the T-pointset, and has up to four neighbour nodes (north, west, south, east). Several nodes on the same
// anchor are repeated knots: a neighbour on the same anchor interval is a knot of multiplicity one more, so
// Bezier end conditions and creases need no zero-length edges in the T-image.
#include <array>
#include <vector>

namespace trivar {

enum class TAnchorKind { vertex, link, face };

struct TNode {
  TAnchorKind kind = TAnchorKind::vertex;
  int anchor = -1;  // vertex, link or face id in the T-image
  int point = -1;   // rational point id in the T-pointset
  std::array<int, 4> neighbours{-1, -1, -1, -1};  // north, west, south, east nodes, -1: none
};

struct TConnect {
  std::vector<TNode> nodes;
};

}  // namespace trivar
