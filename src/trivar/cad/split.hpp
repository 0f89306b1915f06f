#pragma once
// Splitting a V-model by a plane or a B-spline surface: every cell the surface crosses becomes two trimmed
// cells, one on each side, which share the cut as a V-surface; cells on one side stay whole (as trimmed cells
// of the same shape). The cells keep their attributes. Built on the Boolean's general fuse: the tool is the
// region swept from the surface along its normal beyond the model, and the result keeps every piece of the
// model, inside and outside the tool, as a cell of its own.
#include <array>

#include "trivar/cad/boolean.hpp"
#include "trivar/spline/tensor_spline.hpp"

namespace trivar::cad {

struct SplitPlane {
  std::array<double, 3> point{};   // a point of the plane
  std::array<double, 3> normal{};  // any length but zero
};

// "px,py,pz,nx,ny,nz" -> SplitPlane; throws trivar::Error naming the text otherwise.
SplitPlane parse_split_plane(const std::string& text);

// Throws trivar::Error for a zero normal and when the plane misses the model (nothing would be split).
VModel split(const VModel& model, const SplitPlane& plane, const BooleanOptions& options = {},
             BooleanReport* report = nullptr);

// The cut follows the surface (3D, polynomial or rational), which must reach across the model: the tool is
// the surface swept along its mean normal (S_u x S_v) by twice the model's diagonal, so the parts of the
// model on that side of the surface become cells of their own. Throws trivar::Error for a surface that is not
// in 3D or has no mean normal, and when the surface misses the model.
VModel split(const VModel& model, const TensorSpline<2>& surface, const BooleanOptions& options = {},
             BooleanReport* report = nullptr);

}  // namespace trivar::cad
