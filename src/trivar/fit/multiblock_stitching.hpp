#pragma once
// C0 and C1 stitching of multi-block models (seed 004, "C1 stitching" beyond two patches): surfaces (in the plane
// or in space) or volumes, polynomial or rational, whose blocks meet over common parts of their sides, T-joints
// included, with parametrisations that correspond linearly across every interface (the usual multi-patch setting
// after knot-line insertion). The blocks are matched as in multiblock_space (common parts found geometrically,
// side knot lines exchanged over the first two rows for C1, T-joint lines with multiplicity p), and then the
// control values of the B-splines of the first rows (row 0: on the side; row 1: adding to the derivative across
// it) of every interface side move as little as possible (minimum norm, all interfaces at once, so corners
// and T-joints shared by several interfaces are consistent) such that on every common part
//   C0: both blocks' traces are equal;
//   C1: additionally block 1's derivative across the side (into it) equals lambda times block 0's (out of it),
//       lambda > 0 the interface's ratio of parametric speeds (CrossSpeed below).
// Each condition is imposed at p + 1 points per Bezier span of the common part and direction along it, which
// makes the polynomial pieces equal, so the continuity holds everywhere on the seam. Every other control value
// keeps its value bit for bit.
// Rational blocks: the weights are kept. They must be C0 (C1) across every seam already, as they are when the
// blocks are pieces of one NURBS; then the rational map x = (w x) / w is C0 (C1) exactly when the homogeneous map
// (w x) is, because w is positive and continuous (with a continuous derivative), so the conditions above are
// imposed on the homogeneous coordinates w x alone (linear in the unknowns).
#include <vector>

#include "trivar/fit/multiblock_space.hpp"
#include "trivar/fit/patch_stitching.hpp"
#include "trivar/lr/lr_spline.hpp"

namespace trivar {

// lambda per interface. `parametric`: the parametrisations correspond with one scale across the seam and along
// it, so lambda is the ratio of the common part's parameter lengths along the side, block 0's over block 1's (the
// geometric mean of the two directions along a face), 1 for blocks cut from one parametrisation; C1 is then the
// continuity of the derivatives of the map over the blocks' parameter domains placed side by side by that affine
// map, consistent around T-joints. `fitted`: lambda fitted to the input's cross derivatives by least squares (as
// the two-patch stitch), for blocks parametrised with different scales across and along (a long block over
// [0, 1]^2); a badly kinked input then fixes lambda at its kinks' average.
enum class CrossSpeed { parametric, fitted };

template <int D>
struct StitchedBlocks {
  std::vector<LRSpline<D>> blocks;            // matched (refined near their interfaces), continuity enforced
  std::vector<BlockInterface<D>> interfaces;
  std::vector<double> speed;                  // per interface: lambda
  Continuity continuity = Continuity::C1;
  double moved = 0.0;    // largest change of a control value (homogeneous w x when rational)
  double jump = 0.0;     // largest value (C0) or cross-derivative (C1) jump measured after stitching, at points
                         // between the constrained ones, relative to the model's size (per unit parameter)
  int conditions = 0;    // linear conditions imposed (per coordinate)
  int unknowns = 0;      // control values free to move (per coordinate)
};

// Throws trivar::Error with one line for blocks of different degrees, coordinates or rationality, for faces
// that overlap in a plus shape (from matching), for an interface whose cross derivatives point against each
// other (C1: the blocks fold back), for rational blocks whose weights are not C0 (C1) across an interface (naming
// both blocks), and when the conditions cannot be met (the jump after stitching exceeds 1e-9 of the model).
template <int D>
StitchedBlocks<D> stitch_blocks(std::vector<LRSpline<D>> blocks, const StitchOptions& options = {},
                                CrossSpeed speed = CrossSpeed::parametric);

}  // namespace trivar
