#pragma once
// Attribute blending where two V-models overlap (seed 001, Eq. (2), the union blend of Massarwi & Elber):
//
//   A(p) = (d1 A1(p) + d2 A2(p)) / (d1 + d2)   p in V1 and V2
//        = A1(p)                               p in V1 only
//        = A2(p)                               p in V2 only
//
// with d1 = d^{b1}_{i2}(p), the distance from p to the part of the boundary of V1 inside V2, and d2 =
// d^{b2}_{i1}(p) symmetrically. Near the boundary of V1 (inside V2) the weight of A1 vanishes, so A is
// continuous across both boundaries.
#include <span>
#include <string>
#include <vector>

#include "trivar/model/model_boundary.hpp"
#include "trivar/model/vmodel.hpp"
#include "trivar/spline/point_inversion.hpp"

namespace trivar {

// The formula above for given memberships and distances; a1, a2 and out have the same size (a1 is ignored
// when !in1, a2 when !in2). Where both distances vanish (p on both boundaries) the two are averaged. Throws
// trivar::Error when p is in neither model or the sizes differ.
void blend_union(std::span<const double> a1, std::span<const double> a2, bool in1, bool in2, double d1, double d2,
                 std::span<double> out);

// Evaluates the blended attribute of two glued models at model-space points. Membership and the attribute
// values come from point inversion in the cells (bounding-box cull, then PointInverter). The distances are
// to the whole model boundaries (distance_to_boundary): for p in both models they vanish exactly where the
// restricted distances of Eq. (2) do (the closure of the boundary part inside the other model), so the blend
// has the same continuity, though interior weights differ where the nearest boundary point of V1 lies
// outside V2. A caller with the trimmed boundaries of a Boolean can use blend_union() with exact distances.
class UnionBlender {
public:
  // Throws trivar::Error when a model is not glued or the attribute is missing in a cell or has a different
  // number of components in the two models.
  UnionBlender(const VModel& m1, const VModel& m2, std::string attribute);

  int components() const { return components_; }
  // Writes components() values and returns true, or returns false when x lies in neither model.
  bool eval(const double* x, double* out) const;

private:
  struct Side {
    const VModel* model = nullptr;
    ModelBoundary boundary;
    std::vector<PointInverter<3>> inverters;
    std::vector<Box<3>> bounds;
  };
  // The attribute at x if x lies in the side's model.
  bool sample(const Side& side, const double* x, double* out) const;

  std::string attribute_;
  int components_ = 0;
  Side sides_[2];
};

}  // namespace trivar
