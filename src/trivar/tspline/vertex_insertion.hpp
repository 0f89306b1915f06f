#pragma once
// Refinement through the T-spline vertex grid, and the LR refinement it becomes (seed 004, "T-spline vertex
// grid as interface to LR B-splines"). A vertex is inserted with the new edges ("arms") it brings, each running
// from it to the nearest knot line in its direction:
//   single vertex  no arm; the vertex splits an existing edge (a new knot on that line's functions)
//   T-joint        one arm; the vertex lies on an existing edge and the arm crosses the face beside it
//   I-joint        two opposite arms; a new line through the vertex across the face it lies in
//   L-joint        two perpendicular arms; inside a face it leaves an L-shaped face, which the T-image
//                  (rectangular faces, seed 002) does not hold, so it is refused there
// The insertion tells LR refinement (seed 004) the direction to refine in (the axis whose knot value the vertex
// adds: s for a vertical arm or a vertex on a horizontal edge), the value (the vertex's coordinate) and the
// centre of the new B-spline (the vertex): the LR mesh line goes through the vertex over the support of the new
// blending functions (those anchored at the vertex in the refined T-mesh) in the other direction, which refines
// directly in the u-extended box mesh.
#include <array>
#include <vector>

#include "trivar/lr/mesh_rectangle.hpp"
#include "trivar/tspline/t_mesh_builder.hpp"

namespace trivar {

enum class Joint { single, t, i, l };
const char* joint_name(Joint j);

struct VertexInsertion {
  double s = 0, t = 0;
  std::array<bool, 4> arms{};  // new edges towards north, west, south, east
};

// Adds the vertex and its arms to the vertex grid (knot segments of t_mesh_builder) and returns the joint kind.
// Throws trivar::Error when the vertex is outside the domain or already a vertex, a vertex without arms or with
// one arm does not lie on an edge, an arm finds no knot line, or an L-joint lies inside a face.
Joint insert_vertex(std::vector<KnotSegment>& grid, const VertexInsertion& v);

// The LR mesh lines of the insertion, given the refined T-spline (from the grid after insert_vertex).
std::vector<MeshRectangle<2>> lr_refinement(const TSpline& refined, const VertexInsertion& v);

}  // namespace trivar
