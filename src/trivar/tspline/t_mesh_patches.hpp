#pragma once
// A T-mesh with star points as tensor Bezier patches, the form every spline reader takes (GoTools .g2, STEP
// B-spline surfaces, trivar JSON). Each face of the mesh becomes one or more patches over pieces of its own
// (u, v) in [0, 1]^2:
//   exact faces    one rational Bezier patch per Bezier element of the face in its chart: the T-spline exactly
//                  (polynomial when every weight of the element is 1).
//   bicubic faces  one bicubic Bezier patch: the uniform bicubic B-spline of the 4 x 4 points, converted exactly.
//   star faces     subdivided `levels` times towards the star point (Stam): the L-shaped ring of level j,
//                  [h, 2h] x [0, h], [h, 2h]^2 and [0, h] x [h, 2h] with h = 2^-j of the patch frame, is
//                  three bicubic patches of the limit surface, exact; only the corner [0, h]^2, h = 2^-levels,
//                  at the star point is constructed (below) and deviates from the limit surface.
//   subdivided     per quarter (the sub-face of one local Catmull-Clark step, [0, 1/2]^2 etc. of the face): one
//                  bicubic patch, or a star face's rings and corner patch at half scale. Crease faces with equal
//                  intervals alike.
//   crease faces   with unequal knot intervals: the sub-faces are B-spline cells of different sizes (the NURCC
//                  rules insert knots unevenly and subdivide next to an irregular vertex one level further), each
//                  one bicubic piece on its square; four cells that fill a square and are one polynomial (where
//                  the rules were knot insertion) are merged, so one exact patch per polynomial square; at an
//                  irregular corner the corner
//                  patch of a star face at half scale, [0, 2^-(levels + 1)]^2 of the face at that corner, which the
//                  cells round it tile up to. Its sides away from the corner cross cell boundaries (knots of the
//                  limit surface), so there it meets the cells C0 only within the tolerance.
//   averaging faces (odd degree p above 3): each regular sub-face one exact patch of degree p (the uniform
//                  B-spline patch of its points, by interpolation at its (p + 1)^2 nodes); at an irregular corner
//                  the square [0, 2^-levels]^2 the polynomial of degree p through the limit surface at those nodes
//                  (its sides meet the exact patches beside it C0 within the tolerance; no tangent-plane
//                  construction at the star point).
// The corner patch (bicubic Bezier b_ij, i along u' from the star point):
//   b_3j, b_i3  its sides away from the star point: the limit surface's exact cubics there (C0 exactly with
//               the exact patches beside it);
//   b_i0, b_0j  its sides along the two edges out of the star point: cubics from the limit point to the exact
//               end point, leaving the star point along Halstead's limit tangent (chord / 3 long) and ending
//               with the exact tangent of the patch beyond. Built from the same data in the two faces that share
//               the edge, so neighbouring corner patches meet C0 (to rounding);
//   b_11        b_10 + b_01 - b_00, so every corner patch's tangent plane at the star point is the limit
//               tangent plane: the patches around a star point are G1 at the point itself;
//   b_21, b_12  the cross-derivatives of the exact patches beside it (C1 with them along those rows);
//   b_22        the mean of the two cross-derivative choices (the twist of the limit surface is not bicubic).
// Continuity: C2 between exact pieces of one face (one polynomial ring after another), C0 everywhere, G1 at the
// star points, and across the corner patches' sides a normal jump that shrinks with the levels;
// tests/tspline/t_mesh_patches_test.cpp measures all of them. With levels = 0 each star face is a single
// corner patch (h = 1), so every face is one patch and neighbouring faces share whole sides: a conforming
// multipatch layout for analysis.
#include <vector>

#include "trivar/core/box.hpp"
#include "trivar/spline/tensor_spline.hpp"
#include "trivar/tspline/t_mesh_surface.hpp"

namespace trivar {

struct FacePatch {
  int face = -1;
  Box<2> piece;             // the part of the face's (u, v) in [0, 1]^2 it covers: also its parameter domain
  TensorSpline<2> surface;  // one Bezier element, dim 3
  bool exact = true;        // false: the constructed corner patch at a star point
};

struct TMeshPatchOptions {
  double tolerance = 0;  // largest deviation of a corner patch from the limit surface; <= 0: 1e-6 of the
                         // control points' bounding-box diagonal
  int levels = -1;       // >= 0: exactly that many levels; < 0: the fewest meeting the tolerance
  int max_levels = 48;
};

struct TMeshPatches {
  std::vector<FacePatch> patches;
  int levels = 0;
  double deviation = 0;   // max |corner patch(u, v) - limit surface(u, v)| sampled at 9 x 9 points per corner patch
  double tolerance = 0;   // the tolerance applied
  int exact_patches = 0, corner_patches = 0;
};

// Throws trivar::Error when the tolerance is not met within max_levels (naming the deviation reached).
TMeshPatches t_mesh_patches(const TMeshSurface& surface, const TMeshPatchOptions& options = {});

}  // namespace trivar
