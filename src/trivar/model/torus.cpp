#include "trivar/model/torus.hpp"

#include <cmath>
#include <numbers>

#include "trivar/core/error.hpp"
#include "trivar/core/number_format.hpp"
#include "trivar/model/circle_arc.hpp"
#include "trivar/model/revolve.hpp"
#include "trivar/spline/affine_transform.hpp"

namespace trivar {

CellComplex make_torus(const TorusSpec& spec) {
  require(std::isfinite(spec.major_radius) && std::isfinite(spec.minor_radius) && spec.minor_radius > 0 &&
              spec.minor_radius < spec.major_radius,
          "make_torus: radii must satisfy 0 < minor < major, got major " + format_number(spec.major_radius) +
              ", minor " + format_number(spec.minor_radius));
  // (x, y) -> (major + x, 0, -y): the mirror makes S_u x S_v point along +y, the direction of rotation at
  // angle 0, which revolve() turns into det J > 0.
  Eigen::Matrix3d place = Eigen::Matrix3d::Zero();
  place(0, 0) = 1;
  place(2, 1) = -1;
  const Eigen::Vector3d offset(spec.major_radius, 0, 0);
  CellComplex cells;
  for (const auto& section : disk_cells(spec.minor_radius, spec.core))
    cells.push_back(revolve<3>(transform(section, place, offset), Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(),
                               2 * std::numbers::pi));
  return cells;
}

}  // namespace trivar
