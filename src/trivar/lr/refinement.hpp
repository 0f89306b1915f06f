#pragma once
// Refinement strategies for LR splines, with the definitions of the literature (Johannessen, Kvamsdal, Dokken
// 2014) so results compare with other tools:
//   FULLSPAN on element e: in each direction k, the mesh rectangle perpendicular to k through the midpoint of
//     e, spanning in the other directions the union of the supports of all B-splines whose support contains e
//     (a surface: their bounding box; a volume: one rectangle per distinct support cross-section, since the
//     union need not be a box and its bounding box can end inside elements).
//   MINSPAN on element e: as FULLSPAN but, for the rectangle across k, spanning the support of one B-spline
//     whose support contains e: the smallest across k (product of its sides j != k; in 2D its length along the
//     line). Tie-break as LRsplines (so surfaces refine exactly as there): the one most centred on e, i.e. per
//     direction j != k whose numbers of knots up to e's start and before e's end are closest to (p_j + 2) / 2;
//     a later id wins when it is at least as centred in every such direction on both sides.
//   STRUCTURED on B-spline b: for every non-empty knot interval of b in every direction, the mesh rectangle
//     through its midpoint spanning b's support in the other directions.
// All rectangles of one call are computed from the mesh before the call, then inserted as one batch
// (LRSpline::insert(span)); rectangles already in the mesh at their turn are skipped.
//
// Aspect ratio. With max_aspect_ratio = R > 0, a box (the element for FULLSPAN / MINSPAN, the B-spline's
// support for STRUCTURED) is cut in direction k only when its side h_k halved is at least h_max / R, h_max its
// longest side; the longest side is always cut. So boxes whose aspect ratio would exceed R after a full cut
// are refined only in their long directions, and R >= 2 bounds the ratio of refined boxes' sides by R.
#include <span>
#include <string>
#include <vector>

#include "trivar/lr/lr_spline.hpp"
#include "trivar/lr/mesh_rectangle.hpp"

namespace trivar {

enum class Strategy { fullspan, minspan, structured };

// "fullspan", "minspan", "structured"; parse_strategy throws trivar::Error naming an unknown one.
const char* to_string(Strategy s);
Strategy parse_strategy(const std::string& name);

struct RefineOptions {
  Strategy strategy = Strategy::fullspan;
  int multiplicity = 1;           // of every inserted rectangle, 1..p_k + 1
  double max_aspect_ratio = 0.0;  // <= 0: off; otherwise >= 1, see above
};

// The rectangles of FULLSPAN / MINSPAN for the given elements (ids in range, any order; duplicates ignored),
// in ascending element order, directions ascending per element. STRUCTURED here means: STRUCTURED on every
// B-spline whose support contains one of the elements.
template <int D>
std::vector<MeshRectangle<D>> element_rectangles(const LRSpline<D>& lr, std::span<const int> elements,
                                                 const RefineOptions& opts);

// The rectangles of STRUCTURED for the given B-splines, ascending ids. FULLSPAN / MINSPAN here mean: on every
// element of the B-splines' supports.
template <int D>
std::vector<MeshRectangle<D>> function_rectangles(const LRSpline<D>& lr, std::span<const int> functions,
                                                  const RefineOptions& opts);

// Computes the rectangles, inserts them as one batch, and returns how many changed the spline.
template <int D>
int refine_elements(LRSpline<D>& lr, std::span<const int> elements, const RefineOptions& opts);
template <int D>
int refine_functions(LRSpline<D>& lr, std::span<const int> functions, const RefineOptions& opts);

}  // namespace trivar
