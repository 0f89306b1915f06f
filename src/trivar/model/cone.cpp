#include "trivar/model/cone.hpp"

#include <cmath>

#include "trivar/core/error.hpp"
#include "trivar/core/number_format.hpp"
#include "trivar/model/circle_arc.hpp"
#include "trivar/model/ruled.hpp"
#include "trivar/spline/affine_transform.hpp"

namespace trivar {

CellComplex make_cone(const ConeSpec& spec) {
  require(std::isfinite(spec.bottom_radius) && spec.bottom_radius > 0,
          "make_cone: bottom radius must be positive, got " + format_number(spec.bottom_radius));
  require(std::isfinite(spec.top_radius) && spec.top_radius > 0,
          "make_cone: top radius must be positive (a full cone's apex is singular), got " +
              format_number(spec.top_radius));
  require(std::isfinite(spec.height) && spec.height > 0,
          "make_cone: height must be positive, got " + format_number(spec.height));
  const auto bottom = disk_cells(spec.bottom_radius, spec.core);
  const auto top = disk_cells(spec.top_radius, spec.core);
  const Eigen::Vector3d lift(0, 0, spec.height);
  CellComplex cells;
  for (std::size_t c = 0; c < bottom.size(); ++c)
    cells.push_back(ruled<3>(bottom[c], transform(top[c], Eigen::Matrix3d::Identity(), lift)));
  return cells;
}

}  // namespace trivar
