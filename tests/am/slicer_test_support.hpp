#pragma once
// Shared by the slicer tests: the residual every traced pixel must meet, and primitives glued into models.
#include "trivar/model/primitives.hpp"
#include "trivar/model/vmodel.hpp"

namespace trivar::test {

// Pixel centres are inverted to a millionth of a 600-dpi pixel: the default tolerance, 1e-9 of a cell's
// control-box diagonal, on these models of a few millimetres.
constexpr double kResidualBound = 1e-6 * 25.4 / 600;

inline VModel glued(const CellComplex& cells) {
  VModel m;
  for (const auto& c : cells) m.add_cell(VCell(c));
  m.glue();
  return m;
}

}  // namespace trivar::test
