#pragma once
// Dimension of the bivariate spline space over a box mesh with multiplicities (Mourrain, "On the dimension of
// spline spaces on planar T-meshes", 2014; seed 004): piecewise polynomials of bidegree (p_0, p_1) on the
// elements, of smoothness r = p - mu across every interior edge of multiplicity mu (mu = p + 1: discontinuous),
//
//   dim = (p_0+1)(p_1+1) f_2 - sum_{edges on u = const} (p_1+1)(r_0+1) - sum_{edges on v = const} (p_0+1)(r_1+1)
//         + sum_{interior vertices} (r_0+1)(r_1+1) + h,
//
// with f_2 the elements, the interior edges being the pieces of interior mesh lines between consecutive
// vertices, r_0 / r_1 the smoothness across the line u = const / v = const through a vertex (at a T-vertex the
// line that ends there). For constant smoothness this is the seed's
// (p_0+1)(p_1+1) f_2 - (p_0+1)(r_1+1) f_1^h - (r_0+1)(p_1+1) f_1^v + (r_0+1)(r_1+1) f_0.
//
// Assumptions: the homology term h is 0. It is for meshes produced by LR refinement of a tensor mesh (seed 004,
// lecture 3), and by Mourrain's sufficient condition whenever every maximal interior segment not attached to the
// boundary has enough (>= p + 1 for the relevant direction) consecutive edges; for other T-meshes the value is a
// lower bound. Mesh lines keep one multiplicity between vertices and through every vertex (the weights above need
// it; meshes violating it are rejected with trivar::Error).
//
// The hand-in-hand check (seed 004, lecture 4): LR B-splines lie in the spline space, so more B-splines than
// dim proves dependence; exactly dim of them form a basis when they span the space (hand-in-hand refinement).
#include <span>

#include "trivar/core/box.hpp"
#include "trivar/lr/linear_independence.hpp"
#include "trivar/lr/mesh_rectangle.hpp"

namespace trivar {

// Combinatorial counts of a planar box mesh (the seed's f_2, f_1^h, f_1^v, f_0).
struct TMeshCounts {
  int elements = 0;           // f_2
  int edges_const_u = 0;      // interior edges on lines u = const ("vertical", f_1^v)
  int edges_const_v = 0;      // interior edges on lines v = const ("horizontal", f_1^h)
  int interior_vertices = 0;  // f_0: crossings and T-vertices inside the domain
};

// Counts of the mesh given by its rectangles (lines), the domain being their bounding box; boundary lines
// must be present. Throws trivar::Error on a line whose multiplicity changes away from a vertex.
TMeshCounts tmesh_counts(std::span<const MeshRectangle<2>> mesh);

// The seed's closed form for constant smoothness r_k = p_k - 1 ... any r_k in [-1, p_k].
long long dimension_from_counts(const Ints<2>& degrees, const Ints<2>& smoothness, const TMeshCounts& c);

// dim S_p of the mesh, multiplicities included (see the header comment).
long long dimension(std::span<const MeshRectangle<2>> mesh, const Ints<2>& degrees);

struct HandInHand {
  int basis_count = 0;
  long long dimension = 0;
  // not_independent when basis_count > dimension; independent when equal (valid when the B-splines span the
  // space, as LR refinement going hand in hand guarantees); not_tested when fewer (they cannot span).
  Independence status = Independence::not_tested;
  bool matches() const { return basis_count == dimension; }
};

HandInHand hand_in_hand(int basis_count, std::span<const MeshRectangle<2>> mesh, const Ints<2>& degrees);

}  // namespace trivar
