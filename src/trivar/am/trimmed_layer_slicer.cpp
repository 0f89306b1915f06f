#include "trivar/am/trimmed_layer_slicer.hpp"

#include <cmath>

#include "trivar/core/error.hpp"
#include "trivar/model/material_fractions.hpp"

namespace trivar::am {

TrimmedLayerSlicer::TrimmedLayerSlicer(const VModel& model, const SliceOptions& options)
    : model_(model), grid_(slice_grid(model, options)) {
  const std::string name = options.material_attribute.value_or("material");
  int with = 0;
  for (int c = 0; c < model.num_cells(); ++c) {
    require(model.cell(c).is_trimmed(), [&] {
      return "slicer: cell " + std::to_string(c) + " is not trimmed (models mixing trimmed and untrimmed cells are not sliced)";
    });
    with += model.cell(c).has_attribute(name) ? 1 : 0;
  }
  require(with > 0 || !options.material_attribute, [&] { return "slicer: no cell has the material attribute '" + name + "'"; });
  material_.assign(static_cast<std::size_t>(model.num_cells()), nullptr);
  if (with == 0) return;
  for (int c = 0; c < model.num_cells(); ++c) {
    require(model.cell(c).has_attribute(name), [&] {
      return "slicer: cell " + std::to_string(c) + " has no material attribute '" + name + "' but other cells do";
    });
    const Attribute& a = model.cell(c).attribute(name);
    if (c == 0) materials_ = a.components();
    require(a.components() == materials_, [&] {
      return "slicer: material attribute '" + name + "' has " + std::to_string(a.components()) + " components in cell " +
             std::to_string(c) + " but " + std::to_string(materials_) + " in cell 0";
    });
    material_[static_cast<std::size_t>(c)] = &a;
  }
  check_material_fractions(model, name);
}

SliceLayer TrimmedLayerSlicer::slice(int k) const {
  const SliceGrid& g = grid_;
  SliceLayer L;
  L.index = k;
  L.z = g.z(k);
  L.width = g.width;
  L.height = g.height;
  L.cell.assign(static_cast<std::size_t>(g.width) * static_cast<std::size_t>(g.height), -1);
  L.fractions = FractionImage(g.width, g.height, materials_, 0.0f);
  std::vector<LineCrossing> cs;
  std::vector<double> values(static_cast<std::size_t>(materials_));
  for (int j = 0; j < g.height; ++j) {
    int* row = L.cell.data() + static_cast<std::size_t>(j) * static_cast<std::size_t>(g.width);
    for (int c = 0; c < model_.num_cells(); ++c) {
      const VCell& cell = model_.cell(c);
      cell.trim()->axis_crossings(0, {0, g.y(j), L.z}, -INFINITY, INFINITY, cs);
      // Pixels between the (2m)-th and (2m+1)-th crossing are inside.
      for (std::size_t m = 0; m + 1 < cs.size(); m += 2) {
        const int i0 = std::max(0, static_cast<int>(std::ceil((cs[m].t - g.x0) / g.dx - 0.5)));
        const int i1 = std::min(g.width - 1, static_cast<int>(std::floor((cs[m + 1].t - g.x0) / g.dx - 0.5)));
        for (int i = i0; i <= i1; ++i) {
          if (row[i] >= 0) continue;  // the first cell claiming a pixel keeps it
          row[i] = c;
          ++L.stats.inside_pixels;
          float* out = L.fractions.pixel(i, j);
          const Attribute* a = material_[static_cast<std::size_t>(c)];
          if (!a) {
            out[0] = 1.0f;
            continue;
          }
          const Param<3> u{g.x(i), g.y(j), L.z};
          a->eval(cell.geometry(), u, values.data());
          const double sum = material_fraction_sum(values, [&] { return cell_point(c, u); });
          for (int q = 0; q < materials_; ++q) out[q] = static_cast<float>(values[static_cast<std::size_t>(q)] / sum);
        }
      }
    }
  }
  return L;
}

}  // namespace trivar::am
