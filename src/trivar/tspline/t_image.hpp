#pragma once
// The parametric layer of a T-spline (Xiao et al. 2016, "STEP-compliant data exchange of T-spline models"):
// the T-image. T-vertices carry a parameter (s, t) and their outgoing link per direction; T-edges are
// axis-parallel segments between two vertices; a T-link is an edge with an orientation; a T-face is a
// counter-clockwise loop of links around a rectangle (a T-junction is a vertex on a face side, so a side may
// hold several links). Knot multiplicities are not drawn here: they live in the topological layer (t_connect).
#include <array>
#include <string>
#include <vector>

#include "trivar/core/box.hpp"

namespace trivar {

// Directions in the order of the T-vertex and T-node attributes (north, west, south, east): counter-clockwise,
// so turning left is +1 modulo 4.
enum class TDir { north = 0, west = 1, south = 2, east = 3 };
inline constexpr std::array<const char*, 4> kTDirNames{"north", "west", "south", "east"};
// The parametric direction a compass direction moves along (0: s, 1: t) and its sign.
inline constexpr int tdir_axis(int d) { return d % 2 == 0 ? 1 : 0; }
inline constexpr int tdir_sign(int d) { return d == 0 || d == 3 ? 1 : -1; }
inline constexpr int tdir_opposite(int d) { return (d + 2) % 4; }

struct TVertex {
  double s = 0, t = 0;
  std::array<int, 4> links{-1, -1, -1, -1};  // outgoing link per direction (north, west, south, east), -1: none
};

struct TEdge {
  int start = -1, end = -1;  // vertices; start has the smaller varying parameter
};

struct TLink {
  int edge = -1;
  bool sense = true;  // true: from the edge's start to its end
};

struct TFace {
  std::vector<int> loop;  // links, counter-clockwise, each starting where the previous one ends
};

struct TEdgeCondition {
  int edge = -1;
  bool flag = false;  // the exporter's boundary condition flag, kept for exchange
};

struct TImage {
  std::vector<TVertex> vertices;
  std::vector<TEdge> edges;
  std::vector<TLink> links;
  std::vector<TFace> faces;
  std::vector<TEdgeCondition> conditions;

  int link_start(int l) const;  // the vertex a link leaves
  int link_end(int l) const;
  Box<2> face_box(int f) const;
  Box<2> edge_box(int e) const;
  Box<2> domain() const;  // bounding box of the vertices
};

// Throws trivar::Error naming the first inconsistency: ids out of range, an edge that is not axis-parallel or
// has no length, a face loop that is not closed or not a counter-clockwise rectangle (every link on the
// rectangle's boundary, exactly four corners), a vertex link pointer that does not leave the vertex in its
// direction.
void validate(const TImage& image);

// Adds the edge (a, b) (ordered by parameter) and its two links; returns the link from a to b.
int add_edge(TImage& image, int a, int b);
// Sets every vertex's link pointers from the links (each vertex's outgoing link per direction).
void connect_vertex_links(TImage& image);
// "link 7 (vertex 2 -> vertex 5)", for messages.
std::string describe_link(const TImage& image, int l);

}  // namespace trivar
