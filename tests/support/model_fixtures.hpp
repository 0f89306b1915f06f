#pragma once
// Models the model, cad and am tests build again and again: axis-aligned blocks placed in space and V-models
// glued from a list of cells.
#include <Eigen/Core>

#include "trivar/model/block.hpp"
#include "trivar/model/primitives.hpp"
#include "trivar/model/vmodel.hpp"
#include "trivar/spline/affine_transform.hpp"

namespace trivar::test {

// The block [x, x + size_0] x [y, y + size_1] x [z, z + size_2] with the given degrees and elements.
inline TensorSpline<3> block_at(double x, double y, double z, Param<3> size = {1, 1, 1}, Ints<3> degrees = {1, 1, 1},
                                Ints<3> elements = {1, 1, 1}) {
  return transform(make_block<3>(degrees, elements, size), Eigen::Matrix3d::Identity(), Eigen::Vector3d(x, y, z));
}

// The cells, moved by `shift`, as one V-model, glued.
inline VModel glued(const CellComplex& cells, const Eigen::Vector3d& shift = Eigen::Vector3d::Zero()) {
  VModel m;
  for (const auto& c : cells) m.add_cell(VCell(transform(c, Eigen::Matrix3d::Identity(), shift)));
  m.glue();
  return m;
}

}  // namespace trivar::test
