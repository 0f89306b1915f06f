#pragma once
// Global non-uniform Catmull-Clark steps (NURCC, Sederberg, Zheng, Sewell and Sabin 1998) of a whole control mesh:
// every face becomes four, every knot interval is halved (midpoint insertion), and the new points are the face,
// edge and vertex points of the knot-interval-weighted rules of non_uniform_catmull_clark (the same weight
// functions). At vertices of four faces they are exact knot insertion of the bicubic B-spline, and at a star point
// they are the star rule that NonUniformStar iterates, so the limit surface does not change; the steps only move
// star points apart (their distance in edges doubles), so that each star point gets its own three regular rings
// of faces for NonUniformStar's evaluation.
//
// Scope: degree 3, closed meshes (every edge between two faces), quadrilaterals without T-junctions, equal knot
// intervals on opposite sides of every face, one control point per vertex, no sharp creases; anything else is
// refused in one line.
#include <array>
#include <vector>

#include "trivar/tspline/t_mesh.hpp"

namespace trivar {

// One global step. Sub-face c of face f is face 4 f + c of the result: c = 0, 1, 2, 3 the quarters at (u, v) in
// [0, 1/2]^2, [1/2, 1] x [0, 1/2], [1/2, 1]^2, [0, 1/2] x [1/2, 1] of f's frame (first corner link along u), each
// with the same frame orientation. Vertex v keeps its id; edge e's point is vertex V + e and face f's V + E + f.
TMesh nurcc_step(const TMesh& m);

// The global steps that move every two star points at least `apart` edges apart (0 when the mesh has no two
// star points closer, or when its knot intervals are all equal: uniform Catmull-Clark evaluates close star points
// itself); 0 also when the mesh is not one nurcc_step takes (the evaluation then gives its own reason).
int nurcc_steps_needed(const TMesh& m, int apart);

}  // namespace trivar
