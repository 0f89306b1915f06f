#pragma once
// C0 and C1 stitching of two B-spline or LR surfaces that share a side, or two volumes that share a face (seed
// 004, "C1 stitching of 2-variate B-splines", one dimension up): the shared side is found geometrically (any side
// of either patch, any orientation-preserving correspondence of their parameters along it), the second patch is
// re-parametrised to continue the first across that side, the knot lines (planes) of both sides are inserted into
// each as segments spanning the side over the first rows only (LR refinement, geometry unchanged), and continuity
// is enforced on the first rows alone:
//   C0: the two copies of every seam control point become their average;
//   C1: additionally the control points of row 1 on both sides move, as little as possible (least squares),
//       onto the line through the seam point in the ratio of the two seam-adjacent knot spans, which makes the
//       derivative across the seam equal on both sides.
// Every other control point keeps its value bit for bit. The two patches then merge into one LR spline whose
// seam line has multiplicity p (C0) or p - 1 (C1). The second patch's parameter length across the seam is scaled
// so that its cross-seam derivative best matches the first's before the adjustment, so patches that are already
// tangent-continuous (in any parametrisation speed) move by rounding only.
#include "trivar/fit/domain_side.hpp"
#include "trivar/lr/lr_spline.hpp"

namespace trivar {

enum class Continuity { C0, C1 };

struct StitchOptions {
  Continuity continuity = Continuity::C1;
  // Largest distance at which the two sides count as one curve; 0: 1e-8 times the larger bounding-box diagonal
  // of the two control nets.
  double tolerance = 0.0;
};

template <int D>
struct Stitched {
  LRSpline<D> first;   // the first patch in its own parametrisation, knot lines adapted, continuity enforced
  LRSpline<D> second;  // the second patch re-parametrised beyond first's seam side, adapted likewise
  DomainSide seam;     // the side of first's domain that the second patch continues
  Continuity continuity = Continuity::C1;
  double seam_gap = 0.0;  // largest distance between the two sides before stitching (sampled)
  double moved = 0.0;     // largest change of a control point
};

// Rational patches (NURBS, rational LR): the second patch's weights are first scaled to meet the first's along the
// seam (which leaves its geometry unchanged). C0 then averages the seam values in homogeneous form (w x, w). C1
// keeps the weights, which must already be C1 across the seam (pieces of one NURBS), and enforces C1 on the
// homogeneous coordinates w x of the first rows (seam_weights.hpp); the second patch's speed across the seam is
// then the one that makes the weights C1. `moved` is measured in homogeneous values.
// Throws trivar::Error with one line when one patch is rational and the other not, for C1 on rational patches
// whose weights are not C1 across the seam (naming the weight-derivative jump), when they are of another
// parametric or control dimension or degree, share no side, meet along a side with parametrisations that do not
// correspond linearly or with weights that are not proportional along it, or when the second patch would have to
// be mirrored to continue the first (opposite orientation: its normal points the
// other way); for C1 also when the cross-seam derivatives point against each other (the patches fold back).
template <int D>
Stitched<D> stitch(const LRSpline<D>& first, const LRSpline<D>& second, const StitchOptions& options = {});

// The two stitched patches as one LR spline on the union of their domains (first's parametrisation).
template <int D>
LRSpline<D> merge(const Stitched<D>& s);

}  // namespace trivar
