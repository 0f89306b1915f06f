#pragma once
// TrimmedLayerSlicer: one layer of a V-model of trimmed cells. A pixel belongs to the first cell whose trimmed
// boundary encloses its centre; per pixel row each cell's boundary is crossed once by the row's line
// (TrimmedSolid::axis_crossings, positions on the exact faces), so inside pixels follow the trimmed boundary,
// not the cell's box. The materials are the cell's attribute at the pixel centre (a trimmed cell's parameters
// are model coordinates, so no point inversion is needed and the residual is 0).
#include "trivar/am/slice_layer.hpp"
#include "trivar/am/layer_slicer.hpp"
#include "trivar/am/slice_options.hpp"
#include "trivar/model/vmodel.hpp"

namespace trivar::am {

class TrimmedLayerSlicer {
public:
  // Throws trivar::Error for an untrimmed cell, bad options (slice_grid), or a material attribute missing on
  // some cells or with differing component counts. The model must outlive the slicer.
  TrimmedLayerSlicer(const VModel& model, const SliceOptions& options);

  const SliceGrid& grid() const { return grid_; }
  int materials() const { return materials_; }
  // Layer k (0 <= k < grid().layers); thread-safe.
  SliceLayer slice(int k) const;

private:
  const VModel& model_;
  SliceGrid grid_;
  std::vector<const Attribute*> material_;  // per cell, null when the model has no material attribute
  int materials_ = 1;
};

}  // namespace trivar::am
