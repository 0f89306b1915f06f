#include "trivar/model/primitives.hpp"

#include "trivar/core/error.hpp"
#include "trivar/model/block.hpp"
#include "trivar/spline/affine_transform.hpp"

namespace trivar {

CellComplex make_box(const BoxSpec& spec) {
  require(spec.origin.allFinite(), "make_box: origin must be finite");
  const auto block = make_block<3>({1, 1, 1}, {1, 1, 1}, {spec.size[0], spec.size[1], spec.size[2]});
  return {transform(block, Eigen::Matrix3d::Identity(), spec.origin)};
}

}  // namespace trivar
