#pragma once
// Bezier patches (in the plane or in space) that tile a domain or a surface with T-junctions (a corner of one patch inside a side of another) cut
// along the parameter lines through those corners until every side meets its neighbours whole, so that a C0
// multipatch space can identify the functions of shared sides. A cut crosses its patch and may end inside the
// side of the next one, so cutting repeats until no corner lies inside a side (at most a few passes on a
// T-mesh: the cuts are the T-junctions' face extensions). The cuts are exact (split_at: de Casteljau), so the
// geometry is unchanged.
#include <vector>

#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

struct ConformingPatches {
  std::vector<TensorSpline<2>> patches;  // one Bezier element each, dim 2 or 3
  std::vector<int> owner;                // per piece: the index of the patch it was cut from
};

// tol: the distance under which a corner counts as on a side (and corners as equal). Throws trivar::Error when the
// pieces would exceed 64 times the input (cuts that do not settle) or a patch is not one Bezier element.
ConformingPatches conforming_split(std::vector<TensorSpline<2>> patches, double tol);

}  // namespace trivar
